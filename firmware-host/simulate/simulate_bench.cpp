#include "firmware-host/simulate/simulate_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "firmware-host/simulate/actuator_plots.hpp"
#include "firmware-host/simulate/decimated_telemetry.hpp"
#include "firmware-host/simulate/simulation_run.hpp"
#include "firmware-host/simulate/simulation_stats.hpp"
#include "firmware-host/simulate/simulation_summary.hpp"

namespace facectl {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Wall seconds of one simulation of `duration` s; with `outputs`, everything
// `facectl simulate` does without --render (telemetry, statistics, plots, summary).
double time_run(const LoadedConfig& cfg, const SimulationInput& input, double duration,
                bool outputs, const std::filesystem::path& dir) {
  OfflineHead head(cfg, 8);
  const ControllerModel& m = head.model();
  SimulationStats stats(m);
  DecimatedTelemetry telemetry(m, (dir / "telemetry.csv").string(), 10);
  ActuatorPlots plots(m, duration);
  SimulationSinks sinks;
  if (outputs) sinks = {&stats, &telemetry, &plots, nullptr, {}, 25.0};
  const auto start = std::chrono::steady_clock::now();
  const SimulationRun run = run_simulation(head, input, duration, sinks);
  telemetry.close();
  if (outputs) {
    plots.write((dir / "plots").string(), stats.states());
    (void)make_summary(cfg, input, run, stats, head.hardware()).dump(2);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Wall seconds of what the loop does besides ticking: evaluating the input at
// the show rate and publishing it, for `duration` s.
double time_input(const LoadedConfig& cfg, const SimulationInput& input, double duration) {
  OfflineHead head(cfg, 8);
  std::array<double, kMaxFaceSignals> pose{};
  const double period = 1.0 / std::max(1.0, cfg.runtime.show_rate_hz);
  const auto poses = static_cast<long>(duration / period);
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < poses; ++k) {
    input.evaluate(std::fmod(static_cast<double>(k) * period, input.duration()), pose);
    head.send(pose);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int simulate_bench_command(const SimulateBenchOptions& o) {
  try {
    ConfigOverrides overrides;
    if (!o.rig.empty()) overrides.rig_path = o.rig;
    if (!o.show.empty()) overrides.show_path = o.show;
    const LoadedConfig cfg =
        load_config(o.config.empty() ? default_config_path() : o.config, overrides);
    if (!cfg.show) throw ConfigError("expected a show (--show or the runtime config's show)");
    const SimulationInput input = SimulationInput::from_show(*cfg.show);
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "facectl-bench-simulate";
    std::filesystem::create_directories(dir);
    std::vector<double> full, bare, feed;
    for (int k = 0; k < std::max(1, o.runs); ++k) {
      full.push_back(time_run(cfg, input, o.duration_s, true, dir));
      bare.push_back(time_run(cfg, input, o.duration_s, false, dir));
      feed.push_back(time_input(cfg, input, o.duration_s));
    }
    std::filesystem::remove_all(dir);
    const double f = median(full), b = median(bare), in = median(feed);
    const double ticks = o.duration_s * cfg.built.model.rate_hz;
    std::printf("facectl bench simulate: rig %s, show %s, %g s simulated at %g Hz, %d run(s)\n",
                cfg.rig.name.c_str(), cfg.show->name().c_str(), o.duration_s,
                cfg.built.model.rate_hz, std::max(1, o.runs));
    std::printf("  simulate (no render): %8.3f s wall, %7.1fx real time, %6.2f us per tick\n", f,
                o.duration_s / f, f / ticks * 1e6);
    std::printf("  loop without outputs: %8.3f s wall, %7.1fx real time, %6.2f us per tick\n", b,
                o.duration_s / b, b / ticks * 1e6);
    std::printf(
        "  of which the show input (evaluate + publish at the show rate): %.2f us per tick\n",
        in / ticks * 1e6);
    std::printf(
        "  so the controller tick with its simulated buses and plants: %.2f us per tick "
        "(%.1f%% of simulate)\n",
        (b - in) / ticks * 1e6, 100.0 * (b - in) / f);
    std::printf("  outputs (telemetry, statistics, plots, summary): %.2f us per tick (%.1f%%)\n",
                (f - b) / ticks * 1e6, 100.0 * (f - b) / f);
    std::printf("  one hour of show: %.1f s (target 7.2 s, 500x)\n", 3600.0 * f / o.duration_s);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl bench simulate: %s\n", e.what());
    return 2;
  }
}

}  // namespace facectl
