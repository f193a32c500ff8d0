#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <thread>

#include "control/capacity.hpp"
#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "drivers/hid/gamepad_mapping.hpp"
#include "drivers/hid/gamepad_report.hpp"
#include "firmware-host/inputs/show_recorder.hpp"

namespace facectl {

// Puppeteering: a non-real-time input thread that, at `rate_hz`, takes the
// newest gamepad state, maps it onto the head's neutral pose and publishes
// the pose into the controller's latest-value mailbox, as the show player
// does. While the gamepad is disconnected (or before it first connects) it
// publishes nothing, so the controller's input watchdog eases the face to
// neutral. With a recorder, every published pose is also recorded.
class GamepadPuppeteer {
 public:
  // The newest state since the last call; false when nothing new arrived
  // (HidGamepad::latest, or a test's injected reports).
  using Source = std::function<bool(GamepadState&)>;

  GamepadPuppeteer(Source source, GamepadMapping mapping,
                   const std::array<double, kMaxFaceSignals>& neutral,
                   LatestValueMailbox<FaceCommand>& mailbox, double rate_hz,
                   ShowRecorder* recorder = nullptr);
  ~GamepadPuppeteer();
  GamepadPuppeteer(const GamepadPuppeteer&) = delete;
  GamepadPuppeteer& operator=(const GamepadPuppeteer&) = delete;

  void start();
  void stop();  // joins; the recorder is complete after it
  std::uint64_t published() const { return published_.load(std::memory_order_relaxed); }
  bool connected() const { return connected_.load(std::memory_order_relaxed); }

  // One pass of the thread, at `now_ns`: exposed for tests that step it.
  void step(std::int64_t now_ns);

 private:
  Source source_;
  GamepadMapping mapping_;
  std::array<double, kMaxFaceSignals> neutral_;
  LatestValueMailbox<FaceCommand>& mailbox_;
  double rate_hz_;
  ShowRecorder* recorder_;
  GamepadState state_;
  FaceCommand command_;
  std::int64_t t0_ns_ = -1;
  std::atomic<std::uint64_t> published_{0};
  std::atomic<bool> connected_{false};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl
