// The live FAP stream (docs/FAP.md): datagrams sent over loopback to a real
// FapUdpStream bound to 127.0.0.1, which receives and parses them in poll()
// and maps accepted frames onto the default head. The input is split into
// datagrams at each 0xFF byte (never valid in FAP text), so one input can
// carry a header and then frames; each input gets a fresh stream.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>

#include "firmware-host/fap/fap_udp_stream.hpp"
#include "tests/firmware-host/fap/default_fap_head.hpp"

// The head's FAP mapping is built before fuzzing starts, so no input's time
// (-timeout) includes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  facectl::testing::default_fap_head();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const facectl::FapMapping& mapping = facectl::testing::default_fap_head().mapping;
  static const int tx = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  facectl::FapUdpStream stream(mapping, {});
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(stream.port());
  inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  std::size_t sent = 0, begin = 0;
  for (std::size_t i = 0; i <= size; ++i) {
    if (i < size && data[i] != 0xFF) continue;
    if (::sendto(tx, data + begin, i - begin, 0, reinterpret_cast<const sockaddr*>(&to),
                 sizeof to) == static_cast<ssize_t>(i - begin)) {
      ++sent;
    }
    begin = i + 1;
    // Drain as we go: the socket's receive buffer is finite.
    if (sent % 64 == 0) stream.poll();
  }
  stream.poll();
  if (stream.stats().datagrams != sent) std::abort();  // loopback lost a datagram
  std::array<double, facectl::kMaxFaceSignals> pose{};
  stream.latest(pose);
  stream.take_clamps();
  return 0;
}
