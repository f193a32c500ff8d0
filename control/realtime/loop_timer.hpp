#pragma once

#include <cstdint>
#include <ctime>

#include "control/clock.hpp"

namespace facectl {

// Fixed-rate timing with absolute deadlines (clock_nanosleep, TIMER_ABSTIME),
// so that the rate does not drift with the work done per tick. A tick that
// ends after the next deadline is an overrun; missed deadlines are skipped,
// not replayed in a burst.
class LoopTimer {
 public:
  struct Wake {
    std::uint64_t tick = 0;
    std::int64_t now_ns = 0;
    std::int64_t deadline_ns = 0;
    double dt_s = 0.0;            // since the previous wake (period on the first tick)
    double wake_latency_s = 0.0;  // now - deadline
  };

  explicit LoopTimer(double rate_hz);

  void start(std::int64_t now_ns);
  // Sleeps until the next deadline and returns the wake-up.
  Wake wait();
  // Call when the tick's work is done; returns its compute time in seconds.
  double finish();

  std::int64_t period_ns() const { return period_ns_; }
  int consecutive_overruns() const { return consecutive_overruns_; }
  std::uint64_t overruns() const { return overruns_; }
  std::uint64_t skipped_deadlines() const { return skipped_; }

 private:
  std::int64_t period_ns_;
  std::int64_t deadline_ns_ = 0;
  std::int64_t last_wake_ns_ = 0;
  std::uint64_t tick_ = 0;
  int consecutive_overruns_ = 0;
  std::uint64_t overruns_ = 0;
  std::uint64_t skipped_ = 0;
  std::int64_t wake_ns_ = 0;
};

}  // namespace facectl
