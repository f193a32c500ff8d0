#pragma once

#include <array>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/config/fap_stream_config.hpp"
#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_mapping.hpp"
#include "firmware-host/fap/fap_udp_peers.hpp"
#include "firmware-host/fap/udp_listener.hpp"
#include "firmware-host/inputs/show_recorder.hpp"

namespace facectl {

struct FapUdpStats {
  std::uint64_t datagrams = 0;        // received
  std::uint64_t frames = 0;           // played
  std::uint64_t malformed = 0;        // rejected datagrams: not the file format
  std::uint64_t out_of_bounds = 0;    // rejected datagrams: a field past FapUdpLimits
  std::uint64_t refused_senders = 0;  // datagrams from senders off the allow list
  std::uint64_t evicted = 0;          // senders whose state a new sender took
  std::uint64_t held_back = 0;        // good frames of a sender while another was playing
  std::uint64_t kernel_drops = 0;     // dropped by the kernel, receive buffer full (SO_RXQ_OVFL)
  std::uint64_t clamps = 0;           // values clamped to the envelope
  std::size_t peers = 0;              // senders with state now
  std::string last_error;             // of the last rejected datagram of an allowed sender
  std::string last_refused;           // "address:port" of the last sender refused
};

// A live FAP stream over UDP (docs/FAP.md). Each datagram carries complete
// lines of the FAP text format: a header once (again to restart numbering),
// then frames, each a mask line and its values line in the same datagram.
// The same FapReader as for files parses them, and FapUdpLimits bounds every
// field. A datagram is taken whole or not at all: a malformed or
// out-of-bounds one is counted, its error kept, and the last good pose stays.
//
// Every sender address:port has its own numbering and counters; only
// senders on the allow list are heard, at most max_peers at once, and one
// of them plays at a time (another takes over once it has been silent for
// takeover_s). Reading never blocks the real-time tick: either poll() from
// one non-real-time thread, or start() a receiver thread; played poses go to
// the latest-value mailbox the tick reads.
class FapUdpStream {
 public:
  // Binds the socket. Throws ConfigError naming the address when it cannot,
  // or when the address is beyond loopback without allow_remote; warns on
  // stderr when it binds beyond loopback.
  // A recorder, when given, gets every pose played, timed from the first
  // (`run --record-show`); it is the receiving thread's until stop().
  FapUdpStream(const FapMapping& mapping, const FapUdpOptions& options,
               LatestValueMailbox<FaceCommand>* mailbox = nullptr,
               ShowRecorder* recorder = nullptr);
  ~FapUdpStream() = default;
  FapUdpStream(const FapUdpStream&) = delete;
  FapUdpStream& operator=(const FapUdpStream&) = delete;

  std::uint16_t port() const { return listener_.port(); }
  // The socket, for its options (a test shrinks SO_RCVBUF to provoke drops).
  int fd() const { return listener_.fd(); }

  // Handles every datagram already queued, without blocking. Returns the
  // number of frames played. From one thread at a time: while start()'s
  // thread runs, only from it (else std::logic_error; checked on entry, so a
  // poll() still running when start() is called is the caller's race).
  std::size_t poll() { return listener_.poll(); }
  // Waits up to timeout_ms for a datagram, then poll()s.
  std::size_t wait_and_poll(int timeout_ms) { return listener_.wait_and_poll(timeout_ms); }
  // A thread that wait_and_poll()s until stop() (or destruction).
  void start() { listener_.start(); }
  void stop() { listener_.stop(); }

  // The last good pose; false before the first frame.
  bool latest(std::array<double, kMaxFaceSignals>& out) const;
  FapUdpStats stats() const;
  std::vector<FapUdpPeerStats> peer_stats() const;
  // Clamps since the last call (kept up to 1024; the count in stats() is exact).
  std::vector<FapClamp> take_clamps();

 private:
  std::size_t handle(const UdpDatagram& d, std::string_view text);
  void count_arrival(const UdpDatagram& d);
  void reject(FapUdpPeer& peer, const std::string& error, bool out_of_bounds);
  std::size_t take(FapUdpPeer& peer, const std::vector<FapFrame>& frames, std::int64_t now_ns);

  const FapMapping& mapping_;
  const FapUdpOptions options_;
  LatestValueMailbox<FaceCommand>* mailbox_;
  ShowRecorder* recorder_;

  // The receiver's alone (the thread that polls): the readers and FAP
  // states in peers_, and who plays.
  std::uint64_t sequence_ = 0;
  std::optional<FapUdpSender> playing_;  // the sender that plays
  std::int64_t played_ns_ = 0;           // when it last played a frame
  std::int64_t first_played_ns_ = -1;    // the recorded show's time 0

  // Guards what other threads read: the counters, pose, clamps and the
  // sender table's entries. Held only to update them, never while parsing;
  // the tick never takes it (it reads the mailbox).
  mutable std::mutex mutex_;
  FapUdpPeerTable peers_;
  std::optional<FapUdpSender> last_refused_;
  bool has_pose_ = false;
  std::array<double, kMaxFaceSignals> pose_{};
  FapUdpStats stats_;
  std::vector<FapClamp> clamps_;

  // Last: destroyed first, so its thread stops before what it calls into.
  UdpListener listener_;
};

}  // namespace facectl
