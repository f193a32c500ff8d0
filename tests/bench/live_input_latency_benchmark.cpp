// Google Benchmark: how long a live input's datagram takes from sendto() on
// loopback to the face command in the latest-value mailbox the tick reads,
// for the Live Link Face stream and, beside it, the FAP stream. Each runs
// its own receiver thread, as in `facectl run`. Results: docs/PERFORMANCE.md.
#include <arpa/inet.h>
#include <benchmark/benchmark.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>

#include "firmware-host/fap/fap_udp_stream.hpp"
#include "firmware-host/inputs/live_link_face_stream.hpp"
#include "tests/firmware-host/fap/default_fap_head.hpp"
#include "tests/firmware-host/inputs/default_retarget.hpp"

namespace facectl {
namespace {

class Sender {
 public:
  explicit Sender(std::uint16_t port) : fd_(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {
    to_.sin_family = AF_INET;
    to_.sin_port = htons(port);
    to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  }
  ~Sender() { ::close(fd_); }
  void send(const std::string& d) {
    ::sendto(fd_, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to_), sizeof to_);
  }

 private:
  int fd_;
  sockaddr_in to_{};
};

// One datagram per iteration, timed from before sendto() until the mailbox
// holds its command (the receiver thread waits in poll() meanwhile).
template <typename Stream>
void time_to_mailbox(benchmark::State& state, Stream& stream,
                     LatestValueMailbox<FaceCommand>& mailbox,
                     const std::function<std::string(long)>& datagram) {
  stream.start();
  Sender tx(stream.port());
  FaceCommand cmd;
  long n = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    tx.send(datagram(n++));
    const auto give_up = t0 + std::chrono::seconds(1);
    while (!mailbox.consume(cmd)) {
      if (std::chrono::steady_clock::now() > give_up) {
        state.SkipWithError("no command within 1 s");
        return;
      }
    }
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  stream.stop();
}

void BM_LiveLinkFacePacketToMailbox(benchmark::State& state) {
  std::ifstream in(std::string(FACECTL_SOURCE_DIR) +
                       "/tests/firmware-host/inputs/real/live_link_face_udp/"
                       "pylivelinkface_jaw_open_smile_left.bin",
                   std::ios::binary);
  const std::string packet(std::istreambuf_iterator<char>(in), {});
  const HeadConfig& head = testing::default_head_config();
  LatestValueMailbox<FaceCommand> mailbox;
  LiveLinkFaceOptions options;
  options.port = 0;
  LiveLinkFaceStream stream(testing::default_retarget(), head.layout, head.neutral, options,
                            &mailbox);
  time_to_mailbox(state, stream, mailbox, [&](long) { return packet; });
}
BENCHMARK(BM_LiveLinkFacePacketToMailbox)->UseManualTime()->Unit(benchmark::kMicrosecond);

void BM_FapDatagramToMailbox(benchmark::State& state) {
  const auto& fap = testing::default_fap_head();
  LatestValueMailbox<FaceCommand> mailbox;
  FapUdpStream stream(fap.mapping, FapUdpOptions{}, &mailbox);
  // A frame moving the jaw (FAP 3) and the inner brows (31, 32), numbered
  // by iteration; the header comes with the first.
  std::string mask;
  for (int f = 1; f <= 68; ++f) mask += (f == 3 || f == 31 || f == 32) ? "1 " : "0 ";
  time_to_mailbox(state, stream, mailbox, [&](long n) {
    return (n == 0 ? std::string("2.1 bench 25 100000000\n") : std::string()) + mask + "\n" +
           std::to_string(n) + " 300 80 80\n";
  });
}
BENCHMARK(BM_FapDatagramToMailbox)->UseManualTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace facectl
