#pragma once

#include <array>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "control/command/face_command.hpp"
#include "control/command/face_layout.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/config/live_link_face_config.hpp"
#include "firmware-host/fap/udp_listener.hpp"
#include "firmware-host/inputs/retarget_table.hpp"
#include "firmware-host/inputs/show_recorder.hpp"

namespace facectl {

struct LiveLinkFaceStats {
  std::uint64_t datagrams = 0;        // received
  std::uint64_t frames = 0;           // played
  std::uint64_t no_face = 0;          // packets without a face: nothing played
  std::uint64_t malformed = 0;        // not a version 6 packet: never played
  std::uint64_t refused_senders = 0;  // datagrams from senders off the allow list
  std::uint64_t held_back = 0;        // good frames of a sender while another was playing
  std::uint64_t kernel_drops = 0;     // dropped by the kernel, receive buffer full (SO_RXQ_OVFL)
  std::uint64_t clamps = 0;           // weights clamped to 0..1, and signals by the table
  std::string last_error;             // of the last malformed datagram
  std::string subject;                // the playing sender's subject name and device id
  std::string device_id;
};

// The Live Link Face app's UDP stream (docs/INPUTS.md, "Live Link Face
// stream"): each packet's 52 blendshapes go through the head's retargeting
// table, and the head rotation onto the neck, as for a recorded capture.
// A packet is taken whole or not at all: a malformed one is counted, its
// error kept, and nothing is played for it (nor for a packet without a
// face). One sender (address:port) plays at a time; another takes over once
// the one playing has played nothing for takeover_s.
// Played poses go to the latest-value mailbox the tick reads (the input
// watchdog eases the face to neutral when they stop) and, when given, to a
// show recorder (`run --record-show`), timed from the first pose played.
class LiveLinkFaceStream {
 public:
  // Binds the socket: throws ConfigError naming the address when it cannot.
  // `table`, `layout`, `neutral` and `recorder` must outlive the stream;
  // the recorder is the receiving thread's until stop().
  LiveLinkFaceStream(const RetargetTable& table, const FaceLayout& layout,
                     const std::array<double, kMaxFaceSignals>& neutral,
                     const LiveLinkFaceOptions& options,
                     LatestValueMailbox<FaceCommand>* mailbox = nullptr,
                     ShowRecorder* recorder = nullptr);
  ~LiveLinkFaceStream() = default;
  LiveLinkFaceStream(const LiveLinkFaceStream&) = delete;
  LiveLinkFaceStream& operator=(const LiveLinkFaceStream&) = delete;

  std::uint16_t port() const { return listener_.port(); }
  int fd() const { return listener_.fd(); }

  // Handles every datagram already queued, without blocking; returns the
  // frames played. From one thread at a time: while start()'s thread runs,
  // only from it (else std::logic_error).
  std::size_t poll() { return listener_.poll(); }
  // Waits up to timeout_ms for a datagram, then poll()s.
  std::size_t wait_and_poll(int timeout_ms) { return listener_.wait_and_poll(timeout_ms); }
  // A thread that wait_and_poll()s until stop() (or destruction).
  void start() { listener_.start(); }
  void stop() { listener_.stop(); }

  // The last pose played; false before the first.
  bool latest(std::array<double, kMaxFaceSignals>& out) const;
  LiveLinkFaceStats stats() const;

 private:
  struct Sender {
    std::uint32_t address = 0;
    std::uint16_t port = 0;
    bool operator==(const Sender&) const = default;
  };
  std::size_t handle(const UdpDatagram& d, std::string_view bytes);

  const RetargetTable& table_;
  const FaceLayout& layout_;
  const std::array<double, kMaxFaceSignals>& neutral_;
  const LiveLinkFaceOptions options_;
  LatestValueMailbox<FaceCommand>* mailbox_;
  ShowRecorder* recorder_;

  // The receiving thread's alone.
  std::uint64_t sequence_ = 0;
  std::optional<Sender> playing_;
  std::int64_t played_ns_ = 0;
  std::int64_t first_played_ns_ = -1;

  // Guards what other threads read; the tick never takes it (it reads the mailbox).
  mutable std::mutex mutex_;
  bool has_pose_ = false;
  std::array<double, kMaxFaceSignals> pose_{};
  LiveLinkFaceStats stats_;

  // Last: destroyed first, so its thread stops before what it calls into.
  UdpListener listener_;
};

}  // namespace facectl
