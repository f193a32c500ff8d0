#include "control/realtime/loop_timer.hpp"

#include <cerrno>
#include <cmath>
#include <stdexcept>

namespace facectl {

LoopTimer::LoopTimer(double rate_hz)
    : period_ns_(static_cast<std::int64_t>(std::llround(1e9 / rate_hz))) {
  if (!(rate_hz > 0.0) || period_ns_ <= 0) throw std::invalid_argument("loop rate must be > 0");
}

void LoopTimer::start(std::int64_t now_ns) {
  deadline_ns_ = now_ns + period_ns_;
  last_wake_ns_ = now_ns;
  tick_ = 0;
}

LoopTimer::Wake LoopTimer::wait() {
  timespec ts{};
  ts.tv_sec = deadline_ns_ / 1'000'000'000;
  ts.tv_nsec = deadline_ns_ % 1'000'000'000;
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
  wake_ns_ = monotonic_ns();
  Wake w;
  w.tick = tick_++;
  w.now_ns = wake_ns_;
  w.deadline_ns = deadline_ns_;
  w.dt_s = static_cast<double>(wake_ns_ - last_wake_ns_) * 1e-9;
  w.wake_latency_s = static_cast<double>(wake_ns_ - deadline_ns_) * 1e-9;
  last_wake_ns_ = wake_ns_;
  return w;
}

double LoopTimer::finish() {
  const std::int64_t done = monotonic_ns();
  deadline_ns_ += period_ns_;
  if (done > deadline_ns_) {
    // The next deadline has already passed: an overrun. Skip to the first
    // deadline still ahead instead of running a burst of late ticks.
    ++overruns_;
    while (deadline_ns_ < done) {
      deadline_ns_ += period_ns_;
      ++skipped_;
      ++consecutive_overruns_;  // every missed deadline counts toward the storm
    }
  } else {
    consecutive_overruns_ = 0;
  }
  return static_cast<double>(done - wake_ns_) * 1e-9;
}

}  // namespace facectl
