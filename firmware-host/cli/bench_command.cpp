#include "firmware-host/cli/bench_command.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <thread>

#include "control/controller.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/inputs/show_player.hpp"
#include "firmware-host/model/sim_twin.hpp"
#include "firmware-host/run/fault_injection.hpp"
#include "firmware-host/run/realtime_loop.hpp"
#include "firmware-host/run/realtime_thread.hpp"
#include "firmware-host/run/status_line.hpp"

namespace facectl {
namespace {

void print_row(const char* name, const LatencyHistogram& h) {
  std::printf("  %-22s %8.1f %8.1f %8.1f %8.1f %8.1f %10llu\n", name, h.percentile(50) * 1e6,
              h.percentile(90) * 1e6, h.percentile(99) * 1e6, h.percentile(99.9) * 1e6,
              h.max() * 1e6, static_cast<unsigned long long>(h.count()));
}

// Runs `body` on a real-time thread for `seconds`, or until `poll` (called
// every 10 ms with the seconds elapsed) returns true.
void run_for(const RealtimeSettings& rt_settings, double seconds, RealtimeReport& report,
             const std::function<void(const std::atomic<bool>&)>& body,
             const std::function<bool(double)>& poll = {}) {
  std::atomic<bool> stop{false};
  std::thread t = start_realtime_thread(
      rt_settings, [&] { body(stop); }, report);
  const std::int64_t t0 = monotonic_ns();
  while (true) {
    const double elapsed = static_cast<double>(monotonic_ns() - t0) * 1e-9;
    if (elapsed >= seconds || (poll && poll(elapsed))) break;
    std::this_thread::sleep_for(std::chrono::duration<double>(std::min(0.01, seconds - elapsed)));
  }
  stop.store(true);
  t.join();
}

bool live(SafetyState s) {
  return s == SafetyState::kIdle || s == SafetyState::kEnabling || s == SafetyState::kRunning;
}

}  // namespace

int bench_loop_command(const BenchLoopOptions& options) {
  std::unique_ptr<LoadedConfig> cfg;
  std::vector<Injection> injections;
  try {
    for (const std::string& text : options.inject) injections.push_back(parse_injection(text));
    ConfigOverrides o;
    o.rate_hz = options.rate_hz;
    cfg = std::make_unique<LoadedConfig>(
        load_config(options.config.empty() ? default_config_path() : options.config, o));
    if (!cfg->show) throw ConfigError("bench loop: the configuration names no show to play");
    check_injection_buses(injections, cfg->rig);
    if (!(options.duration_s > 0.0) || !(options.chunk_s > 0.0)) {
      throw ConfigError("bench loop: --duration and --chunk must be > 0");
    }

  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl bench loop: %s\n", e.what());
    return 2;
  }
  const ControllerModel& model = cfg->built.model;
  RealtimeReport report;
  keep_off_realtime_cpu(cfg->runtime.realtime, report);
  auto hw = make_sim_hardware(model, cfg->rig);
  LatestValueMailbox<FaceCommand> mailbox;
  SpscRing<TelemetryRecord> telemetry(cfg->runtime.telemetry_ring);
  SpscRing<TransitionEvent> events(256);
  Controller controller(model, hw->seams, hw->io, {&mailbox, &telemetry, &events});
  ShowPlayer player(*cfg->show, mailbox, cfg->runtime.show_rate_hz, true);
  player.start();
  controller.request_enable();

  // A telemetry drain stands in for the logger thread, so the pipeline does
  // the same work as in `facectl run --record`.
  std::atomic<bool> drain_stop{false};
  std::thread drain([&] {
    while (!drain_stop.load()) {
      while (telemetry.front() != nullptr) telemetry.pop();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });

  LoopStats bare;
  LoopStats full;
  const RealtimeSettings& rt = cfg->runtime.realtime;
  double done = 0.0;  // pipeline seconds
  std::optional<double> left_running_at;
  while (done < options.duration_s && !left_running_at) {
    const double chunk = std::min(options.chunk_s, options.duration_s - done);
    run_for(rt, chunk, report,
            [&](const std::atomic<bool>& stop) { run_bare_loop(model.rate_hz, stop, bare); });
    RealtimeLoop loop(controller, model.rate_hz, full);
    // A pipeline that faults is no longer the pipeline being measured: stop there.
    const auto watch = [&](double elapsed) {
      fire_due_injections(
          injections, done + elapsed, hw.get(), [&player] { player.go_silent(); }, &loop);
      if (!live(controller.state())) left_running_at = done + elapsed;
      return left_running_at.has_value();
    };
    run_for(
        rt, chunk, report, [&](const std::atomic<bool>& stop) { loop.run(stop); }, watch);
    done += left_running_at ? *left_running_at - done : chunk;
  }
  drain_stop.store(true);
  drain.join();
  player.stop();
  while (const TransitionEvent* ev = events.front()) {
    if (ev->to != SafetyState::kEnabling && ev->to != SafetyState::kRunning) print_transition(*ev);
    events.pop();
  }

  const double period_us = 1e6 / model.rate_hz;
  const double ratio = full.wake_latency.percentile(99) / bare.wake_latency.percentile(99);
  const double compute_share = full.compute.percentile(99) * 1e6 / period_us;
  std::printf("facectl bench loop: %.0f Hz, %.1f s per variant interleaved in %.1f s chunks\n",
              model.rate_hz, done, options.chunk_s);
  std::printf("  real-time: SCHED_FIFO %s, memory locked %s, pinned %s\n",
              report.fifo ? "yes" : "no", report.memory_locked ? "yes" : "no",
              report.pinned ? "yes" : "no");
  for (const auto& w : report.warnings) std::printf("  warning: %s\n", w.c_str());
  std::printf(
      "  wake-up latency (us)         p50      p90      p99    p99.9      max    samples\n");
  print_row("bare clock_nanosleep", bare.wake_latency);
  print_row("full pipeline", full.wake_latency);
  std::printf("  p99 ratio pipeline/bare: %.3f (target <= 1.2)\n", ratio);
  std::printf(
      "  tick compute (us)            p50      p90      p99    p99.9      max    samples\n");
  print_row("full pipeline", full.compute);
  std::printf("  tick compute p99: %.2f%% of the %.0f us period (target <= 5%%)\n",
              compute_share * 100.0, period_us);
  std::printf(
      "  over all chunks: overruns (ticks ending past the next deadline) bare %llu, pipeline "
      "%llu; missed deadlines bare %llu, pipeline %llu; controller state %s\n",
      static_cast<unsigned long long>(bare.overruns.load()),
      static_cast<unsigned long long>(full.overruns.load()),
      static_cast<unsigned long long>(bare.skipped.load()),
      static_cast<unsigned long long>(full.skipped.load()),
      std::string(to_string(controller.state())).c_str());
  if (left_running_at) {
    std::printf(
        "  MEASUREMENT STOPPED: the pipeline entered %s after %.2f s; the figures above cover "
        "the ticks up to then\n",
        std::string(to_string(controller.state())).c_str(), *left_running_at);
    return 1;
  }
  return 0;
}

}  // namespace facectl
