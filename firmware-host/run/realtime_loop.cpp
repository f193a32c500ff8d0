#include "firmware-host/run/realtime_loop.hpp"

#include <algorithm>

namespace facectl {
namespace {

void record_wake(LoopStats& stats, const LoopTimer::Wake& w) {
  if (w.tick == 0) stats.first_wake_ns.store(w.now_ns, std::memory_order_relaxed);
  stats.last_wake_ns.store(w.now_ns, std::memory_order_relaxed);
  stats.wake_latency.record(w.wake_latency_s);
  stats.ticks.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

double LoopStats::measured_rate_hz() const {
  const std::uint64_t n = ticks.load(std::memory_order_relaxed);
  const std::int64_t span =
      last_wake_ns.load(std::memory_order_relaxed) - first_wake_ns.load(std::memory_order_relaxed);
  return n < 2 || span <= 0 ? 0.0 : static_cast<double>(n - 1) / (static_cast<double>(span) * 1e-9);
}

void RealtimeLoop::run(const std::atomic<bool>& stop) {
  // The stats add up over runs (`bench loop` runs the loop in chunks).
  const std::uint64_t overruns_before = stats_.overruns.load(std::memory_order_relaxed);
  const std::uint64_t skipped_before = stats_.skipped.load(std::memory_order_relaxed);
  LoopTimer timer(rate_hz_);
  const std::int64_t t0 = monotonic_ns();
  stats_.start_ns.store(t0, std::memory_order_relaxed);
  timer.start(t0);
  const double period = static_cast<double>(timer.period_ns()) * 1e-9;
  double compute = 0.0;
  while (!stop.load(std::memory_order_relaxed)) {
    const LoopTimer::Wake w = timer.wait();
    record_wake(stats_, w);
    TickTiming t;
    t.tick = w.tick;
    t.now_ns = w.now_ns;
    t.time_s = static_cast<double>(w.now_ns - t0) * 1e-9;
    t.dt_s = w.tick == 0 ? period : w.dt_s;  // the real dt, a late tick's included
    t.wake_latency_s = w.wake_latency_s;
    t.compute_s = compute;
    t.consecutive_overruns = timer.consecutive_overruns();
    controller_.tick(t);
    // Fault rehearsal only (`--inject overrun_storm`, simulated hardware):
    // one relaxed load per tick when unused.
    while (monotonic_ns() < stall_until_ns_.load(std::memory_order_relaxed)) {
    }
    compute = timer.finish();
    stats_.compute.record(compute);
    stats_.overruns.store(overruns_before + timer.overruns(), std::memory_order_relaxed);
    stats_.skipped.store(skipped_before + timer.skipped_deadlines(), std::memory_order_relaxed);
  }
}

void run_bare_loop(double rate_hz, const std::atomic<bool>& stop, LoopStats& stats) {
  const std::uint64_t overruns_before = stats.overruns.load(std::memory_order_relaxed);
  const std::uint64_t skipped_before = stats.skipped.load(std::memory_order_relaxed);
  LoopTimer timer(rate_hz);
  timer.start(monotonic_ns());
  while (!stop.load(std::memory_order_relaxed)) {
    const LoopTimer::Wake w = timer.wait();
    record_wake(stats, w);
    stats.compute.record(timer.finish());
    stats.overruns.store(overruns_before + timer.overruns(), std::memory_order_relaxed);
    stats.skipped.store(skipped_before + timer.skipped_deadlines(), std::memory_order_relaxed);
  }
}

}  // namespace facectl
