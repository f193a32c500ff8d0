#pragma once

#include <atomic>
#include <thread>

#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/inputs/show.hpp"

namespace facectl {

// Non-real-time input thread: evaluates a show at a fixed rate and publishes
// each pose into the controller's latest-value mailbox.
class ShowPlayer {
 public:
  ShowPlayer(const Show& show, LatestValueMailbox<FaceCommand>& mailbox, double rate_hz, bool loop);
  ~ShowPlayer();
  ShowPlayer(const ShowPlayer&) = delete;
  ShowPlayer& operator=(const ShowPlayer&) = delete;

  void start();
  void stop();
  // Stops publishing without ending the thread (fault injection: the input goes silent).
  void go_silent() { silent_.store(true, std::memory_order_relaxed); }
  bool finished() const { return finished_.load(std::memory_order_relaxed); }

 private:
  void run();

  const Show& show_;
  LatestValueMailbox<FaceCommand>& mailbox_;
  double rate_hz_;
  bool loop_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> silent_{false};
  std::atomic<bool> finished_{false};
};

}  // namespace facectl
