#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <thread>

#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/inputs/show.hpp"
#include "firmware-host/inputs/show_recorder.hpp"

namespace facectl {

// Non-real-time input thread: evaluates a show (or any timed poses: a
// recorded input's PoseTrack) at a fixed rate and publishes each pose into the
// controller's latest-value mailbox; with a recorder, also records what it
// published (`--record-show`), read only after stop().
class ShowPlayer {
 public:
  using PoseSource = std::function<void(double t, std::array<double, kMaxFaceSignals>& out)>;

  ShowPlayer(const Show& show, LatestValueMailbox<FaceCommand>& mailbox, double rate_hz, bool loop);
  ShowPlayer(PoseSource source, double duration_s, LatestValueMailbox<FaceCommand>& mailbox,
             double rate_hz, bool loop, ShowRecorder* recorder = nullptr);
  ~ShowPlayer();
  ShowPlayer(const ShowPlayer&) = delete;
  ShowPlayer& operator=(const ShowPlayer&) = delete;

  void start();
  void stop();
  // Stops publishing without ending the thread (fault injection: the input goes silent).
  void go_silent() { silent_.store(true, std::memory_order_relaxed); }
  bool finished() const { return finished_.load(std::memory_order_relaxed); }
  // Times the poses by `clock` (the second of the track at a CLOCK_MONOTONIC
  // time: the sound's, `facectl run --audio`) instead of its own start.
  // Before start(); a clocked player does not loop.
  using Clock = std::function<double(std::int64_t now_ns)>;
  void follow(Clock clock) {
    clock_ = std::move(clock);
    loop_ = false;
  }
  // Once it has played to its end (not looping), publish nothing more, so
  // that a mix (InputMixer) gives its signals to the next source. Before start().
  void give_way_when_finished() { give_way_ = true; }

 private:
  void run();

  PoseSource source_;
  Clock clock_;
  double duration_s_;
  LatestValueMailbox<FaceCommand>& mailbox_;
  ShowRecorder* recorder_;
  double rate_hz_;
  bool loop_;
  bool give_way_ = false;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> silent_{false};
  std::atomic<bool> finished_{false};
};

}  // namespace facectl
