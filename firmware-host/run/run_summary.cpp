#include "firmware-host/run/run_summary.hpp"

#include <cmath>
#include <cstdio>

namespace facectl {

int print_run_summary(const RunSummaryInput& in) {
  const ControllerModel& m = in.model;
  const ControllerCounters& c = in.controller.counters();
  const LoopStats& s = in.stats;
  const double rate = s.measured_rate_hz();
  const double period = 1.0 / m.rate_hz;

  std::printf("facectl run summary\n");
  std::printf("  head %s, rig %s: %zu actuators on %zu buses (%s)\n", in.head_name.c_str(),
              in.rig_name.c_str(), m.actuators.size(), m.buses.size(),
              in.real_hardware ? "real hardware" : "simulated");
  std::printf("  real-time: SCHED_FIFO %s, memory locked %s, pinned %s\n",
              in.realtime.fifo ? "yes" : "no", in.realtime.memory_locked ? "yes" : "no",
              in.realtime.pinned ? "yes" : "no");
  std::printf("  ticks %llu, configured rate %.3f Hz, measured rate %.4f Hz (%+.4f%%)\n",
              static_cast<unsigned long long>(s.ticks.load()), m.rate_hz, rate,
              (rate / m.rate_hz - 1.0) * 100.0);
  std::printf("  clock: telemetry time_s 0 is CLOCK_MONOTONIC %.6f s\n",
              static_cast<double>(s.start_ns.load()) * 1e-9);
  std::printf("  wake latency: p50 %.0f us, p99 %.0f us, p99.9 %.0f us, max %.0f us\n",
              s.wake_latency.percentile(50) * 1e6, s.wake_latency.percentile(99) * 1e6,
              s.wake_latency.percentile(99.9) * 1e6, s.wake_latency.max() * 1e6);
  std::printf("  tick compute: p50 %.0f us, p99 %.0f us (%.1f%% of the period), max %.0f us\n",
              s.compute.percentile(50) * 1e6, s.compute.percentile(99) * 1e6,
              s.compute.percentile(99) / period * 100.0, s.compute.max() * 1e6);
  std::printf("  overruns %llu (missed deadlines %llu)\n",
              static_cast<unsigned long long>(s.overruns.load()),
              static_cast<unsigned long long>(s.skipped.load()));

  std::uint64_t hits[6] = {};
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    for (std::size_t b = 0; b < 6; ++b) hits[b] += c.limit_hits[i][b];
  }
  std::printf("  limit breaches %llu\n", static_cast<unsigned long long>(c.limit_breaches));
  std::printf(
      "  limiter engagements (actuator-ticks): position %llu, velocity %llu, acceleration %llu, "
      "jerk %llu, approach %llu\n",
      static_cast<unsigned long long>(hits[0]), static_cast<unsigned long long>(hits[1]),
      static_cast<unsigned long long>(hits[2]), static_cast<unsigned long long>(hits[3]),
      static_cast<unsigned long long>(hits[4]));
  std::printf("  coupled face limits projected on %llu ticks\n",
              static_cast<unsigned long long>(c.coupled_projections));
  if (m.actuator_constraints.size() != 0) {
    std::printf(
        "  actuator coupled limits: targets projected on %llu ticks, bounds shaped steps on "
        "%llu ticks\n",
        static_cast<unsigned long long>(c.actuator_coupled_projections),
        static_cast<unsigned long long>(c.actuator_coupled_steps));
  }
  std::printf("  envelope clamps %llu ticks, rejected input values %llu, stale-input ticks %llu\n",
              static_cast<unsigned long long>(c.envelope_clamps),
              static_cast<unsigned long long>(in.controller.sanitizer().rejected_total()),
              static_cast<unsigned long long>(c.stale_ticks));
  if (m.envelope_widened) std::printf("  WARNING: mandible envelope widened by override\n");

  bool lost = false;
  if (in.writer != nullptr) {
    const TelemetryWriter& w = *in.writer;
    lost = w.dropped() > 0 || w.lost() > 0 || w.write_failed();
    if (w.write_failed()) {
      std::printf("  TELEMETRY WRITE FAILED: %s is incomplete: %s\n", w.path().c_str(),
                  w.error().c_str());
    }
    if (w.drain_cut_short()) {
      std::printf("  TELEMETRY DRAIN CUT SHORT: %s did not take the last rows in time\n",
                  w.path().c_str());
    }
    std::printf("  telemetry: %llu rows written to %s, %llu lost, %llu dropped\n",
                static_cast<unsigned long long>(w.written()), w.path().c_str(),
                static_cast<unsigned long long>(w.lost()),
                static_cast<unsigned long long>(w.dropped()));
  }
  if (in.events_dropped > 0) {
    std::printf("  %llu STATE TRANSITIONS NOT LOGGED (event ring full)\n",
                static_cast<unsigned long long>(in.events_dropped));
    lost = true;
  }
  const SafetyState final_state = in.controller.state();
  const bool faulted = in.controller.faults_seen() > 0;
  std::printf("  final state %s, faults %s\n", std::string(to_string(final_state)).c_str(),
              faulted ? "YES" : "none");

  if (in.controller.stop_timed_out()) {
    std::printf("  STOP TIMEOUT: outputs were disabled before every actuator reached rest\n");
  }
  if (faulted) return 3;
  if (c.limit_breaches > 0 || lost || in.controller.stop_timed_out()) return 1;
  return 0;
}

}  // namespace facectl
