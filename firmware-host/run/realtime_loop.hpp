#pragma once

#include <atomic>
#include <cstdint>

#include "control/controller.hpp"
#include "control/realtime/latency_histogram.hpp"
#include "control/realtime/loop_timer.hpp"

namespace facectl {

// What the loop measured; readable from other threads while it runs. The
// counts add up when the same stats serve several runs.
struct LoopStats {
  LatencyHistogram wake_latency;
  LatencyHistogram compute;
  std::atomic<std::uint64_t> ticks{0};
  std::atomic<std::uint64_t> overruns{0};
  std::atomic<std::uint64_t> skipped{0};
  std::atomic<std::int64_t> first_wake_ns{0};
  // CLOCK_MONOTONIC (ns) of the last run's start: telemetry's time_s 0, so
  // telemetry lines up with other programs' clocks (packets sent, audio).
  std::atomic<std::int64_t> start_ns{0};
  std::atomic<std::int64_t> last_wake_ns{0};

  // Mean tick rate between the first and the last wake-up.
  double measured_rate_hz() const;
};

// Runs the controller at a fixed rate with absolute deadlines until `stop`.
// Meant to be the body of the real-time thread.
class RealtimeLoop {
 public:
  RealtimeLoop(Controller& controller, double rate_hz, LoopStats& stats)
      : controller_(controller), rate_hz_(rate_hz), stats_(stats) {}

  void run(const std::atomic<bool>& stop);

  // Test hook for overrun storms: the tick busy-waits until this time (monotonic ns).
  void stall_until(std::int64_t ns) { stall_until_ns_.store(ns, std::memory_order_relaxed); }

 private:
  Controller& controller_;
  double rate_hz_;
  LoopStats& stats_;
  std::atomic<std::int64_t> stall_until_ns_{0};
};

// A loop that only sleeps to absolute deadlines and records its wake-up
// latency: the baseline `facectl bench loop` compares the pipeline with.
void run_bare_loop(double rate_hz, const std::atomic<bool>& stop, LoopStats& stats);

}  // namespace facectl
