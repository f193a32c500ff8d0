#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_mapping.hpp"

namespace facectl {

struct FapUdpOptions {
  std::string bind_address = "127.0.0.1";  // loopback unless configured otherwise
  std::uint16_t port = 0;                  // 0: the system picks one (see port())
};

struct FapUdpStats {
  std::uint64_t datagrams = 0;  // received
  std::uint64_t frames = 0;     // accepted
  std::uint64_t malformed = 0;  // rejected datagrams
  std::uint64_t clamps = 0;     // values clamped to the envelope
  std::string last_error;       // of the last rejected datagram
};

// A live FAP stream over UDP (docs/FAP.md). Each datagram carries complete
// lines of the FAP text format: a header once (again to restart numbering),
// then frames, each a mask line and its values line in the same datagram.
// The same FapReader as for files parses them. A datagram is taken whole or
// not at all: a malformed one is counted, its error kept, and the last good
// pose stays. Reading never blocks the real-time tick: either poll() from a
// non-real-time thread, or start() a receiver thread; accepted poses go to the
// latest-value mailbox the tick reads.
class FapUdpStream {
 public:
  // Binds the socket. Throws ConfigError naming the address when it cannot.
  FapUdpStream(const FapMapping& mapping, const FapUdpOptions& options,
               LatestValueMailbox<FaceCommand>* mailbox = nullptr);
  ~FapUdpStream();
  FapUdpStream(const FapUdpStream&) = delete;
  FapUdpStream& operator=(const FapUdpStream&) = delete;

  std::uint16_t port() const { return port_; }

  // Handles every datagram already queued, without blocking. Returns the
  // number of frames accepted.
  std::size_t poll();
  // Waits up to timeout_ms for a datagram, then poll()s.
  std::size_t wait_and_poll(int timeout_ms);
  // A thread that wait_and_poll()s until stop() (or destruction).
  void start();
  void stop();

  // The last good pose; false before the first frame.
  bool latest(std::array<double, kMaxFaceSignals>& out) const;
  FapUdpStats stats() const;
  // Clamps since the last call (kept up to 1024; the count in stats() is exact).
  std::vector<FapClamp> take_clamps();

 private:
  void handle(std::string_view datagram, const std::string& peer);

  const FapMapping& mapping_;
  LatestValueMailbox<FaceCommand>* mailbox_;
  int fd_ = -1;
  std::uint16_t port_ = 0;
  std::string bound_;
  FapReader reader_;
  FapState state_;
  std::vector<char> buffer_;
  std::uint64_t sequence_ = 0;

  mutable std::mutex mutex_;  // guards what other threads read: pose, stats, clamps
  bool has_pose_ = false;
  std::array<double, kMaxFaceSignals> pose_{};
  FapUdpStats stats_;
  std::vector<FapClamp> clamps_;

  std::thread thread_;
  std::atomic<bool> running_{false};
};

}  // namespace facectl
