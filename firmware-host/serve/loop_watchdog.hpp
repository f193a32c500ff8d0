#pragma once

#include <chrono>
#include <cstdint>

namespace facectl {

// Whether the real-time loop still ticks, judged once a period from its tick
// count: what `facectl serve` pets systemd's watchdog on (WatchdogSec in
// facectl.service). A stalled tick, not a stalled service thread, is what must
// let systemd restart the head, so a look with an unmoved count says dead.
class LoopWatchdog {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LoopWatchdog(Clock::duration period, Clock::time_point start = Clock::now())
      : period_(period), last_look_(start) {}

  // True once `period` has passed since the last look; alive() then says
  // whether `ticks` moved since it.
  bool look(std::uint64_t ticks, Clock::time_point now) {
    if (now - last_look_ < period_) return false;
    alive_ = ticks != last_ticks_;
    last_ticks_ = ticks;
    last_look_ = now;
    return true;
  }

  bool alive() const { return alive_; }

 private:
  Clock::duration period_;
  Clock::time_point last_look_;
  std::uint64_t last_ticks_ = 0;
  bool alive_ = true;
};

}  // namespace facectl
