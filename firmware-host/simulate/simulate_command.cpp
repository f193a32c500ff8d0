#include "firmware-host/simulate/simulate_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/report/html_report.hpp"
#include "firmware-host/simulate/actuator_plots.hpp"
#include "firmware-host/simulate/decimated_telemetry.hpp"
#include "firmware-host/simulate/output_size.hpp"
#include "firmware-host/simulate/progress_bar.hpp"
#include "firmware-host/simulate/render_sequence.hpp"
#include "firmware-host/simulate/simulation_run.hpp"
#include "firmware-host/simulate/simulation_stats.hpp"
#include "firmware-host/simulate/simulation_summary.hpp"
#include "firmware-host/simulate/staged_dir.hpp"

namespace facectl {
namespace {

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(path.filename().string() + ": cannot write");
}

// Ticks per telemetry.csv row.
std::uint64_t telemetry_every(const SimulateOptions& o, const ControllerModel& m) {
  // Clamped: a rate near 0 would overflow the cast (one row then, at most).
  return static_cast<std::uint64_t>(
      std::clamp(std::round(m.rate_hz / o.telemetry_rate_hz), 1.0, 1e15));
}

// The rig with the runtime config, and the show or FAP file: everything that
// can be wrong with the input, checked before anything is written.
struct Inputs {
  LoadedConfig cfg;
  std::unique_ptr<SimulationInput> input;
};

Inputs load_inputs(const SimulateOptions& o) {
  if (o.rig.empty()) throw ConfigError("--rig: expected a rig file, found none");
  if (o.show.empty() + o.fap.empty() + o.input.empty() != 2) {
    throw ConfigError("expected exactly one of --show FILE, --fap FILE and --input FILE");
  }
  std::optional<InputFormat> format;
  if (!o.format.empty()) {
    format = parse_input_format(o.format);
    if (!format) {
      throw ConfigError("--format: expected one of " + input_format_names() + ", found '" +
                        o.format + "'");
    }
    if (o.input.empty()) throw ConfigError("--format: expected --input FILE with it");
  }
  if (o.out.empty()) throw ConfigError("--out: expected an output folder, found none");
  if (!(o.telemetry_rate_hz > 0.0) || !std::isfinite(o.telemetry_rate_hz)) {
    throw ConfigError("--telemetry-rate: expected a rate above 0 Hz, found " +
                      std::to_string(o.telemetry_rate_hz));
  }
  if (!(o.duration_s >= 0.0) || !std::isfinite(o.duration_s)) {
    throw ConfigError("--duration: expected seconds >= 0, found " + std::to_string(o.duration_s));
  }
  // DIR is replaced as a whole: never a folder that is not an earlier output.
  const std::filesystem::path out(o.out);
  if (std::filesystem::exists(out) && !std::filesystem::is_empty(out) &&
      !std::filesystem::exists(out / "summary.json")) {
    throw ConfigError("--out " + o.out +
                      ": expected a new folder or an earlier `facectl simulate` output (with "
                      "summary.json), found another folder; not replacing it");
  }
  Inputs in;
  ConfigOverrides overrides;
  overrides.rig_path = o.rig;
  in.cfg = load_config(o.config.empty() ? default_config_path() : o.config, overrides);
  in.input = std::make_unique<SimulationInput>(
      !o.input.empty() ? SimulationInput::load_input(in.cfg, o.input, format)
      : o.show.empty() ? SimulationInput::load_fap(in.cfg, o.fap)
                       : SimulationInput::load_show(in.cfg, o.show));
  return in;
}

// Refuses, before anything is written, a run that is longer than any input
// may be or whose outputs could outgrow what the user allowed.
// Returns the bytes left to render frames.
std::uint64_t check_run_size(const SimulateOptions& o, const Inputs& in, double duration_s) {
  if (duration_s > kMaxShowSeconds) {
    throw ConfigError("--duration: expected at most " + std::to_string(kMaxShowSeconds) +
                      " s of show, found " + std::to_string(duration_s));
  }
  if (!(o.max_output_mb > 0.0) || !std::isfinite(o.max_output_mb)) {
    throw ConfigError("--max-output-mb: expected a size above 0, found " +
                      std::to_string(o.max_output_mb));
  }
  const ControllerModel& m = in.cfg.built.model;
  const double mb =
      static_cast<double>(simulate_output_bytes_at_most(m, duration_s, telemetry_every(o, m))) /
      1e6;
  if (mb > o.max_output_mb) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "--out: the outputs of %.0f s of show could take up to %.0f MB, above "
                  "--max-output-mb %.0f; raise it, or lower --duration or --telemetry-rate",
                  duration_s, mb, o.max_output_mb);
    throw ConfigError(text);
  }
  const double left = (o.max_output_mb - mb) * 1e6;
  return left >= 1.8e19 ? UINT64_MAX : static_cast<std::uint64_t>(left);
}

}  // namespace

int simulate_command(const SimulateOptions& o) {
  Inputs in;
  try {
    in = load_inputs(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl simulate: %s\n", e.what());
    return 2;
  }
  const SimulationInput& input = *in.input;
  const double duration = o.duration_s > 0.0 ? o.duration_s : input.duration();
  std::uint64_t frame_bytes = 0;
  try {
    frame_bytes = check_run_size(o, in, duration);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl simulate: %s\n", e.what());
    return 2;
  }
  try {
    StagedDir dir(o.out);
    OfflineHead head(in.cfg, 8);
    const ControllerModel& m = head.model();
    SimulationStats stats(m);
    DecimatedTelemetry telemetry(m, (dir.path() / "telemetry.csv").string(), telemetry_every(o, m));
    ActuatorPlots plots(m, duration);
    ProgressBar progress(duration, !o.quiet && ProgressBar::stderr_is_terminal());
    SimulationSinks sinks{&stats, &telemetry, &plots, &progress, {}, 25.0};
    std::unique_ptr<RenderSequence> render;
    if (o.render) {
      RenderOptions options;
      options.max_bytes = frame_bytes;
      render = std::make_unique<RenderSequence>(in.cfg, dir.path(), options);
      sinks.frame_rate_hz = RenderOptions{}.fps;
      sinks.frame = [&](std::span<const double> face, std::span<const double> positions) {
        render->add_frame(face, positions);
      };
    }
    const SimulationRun run = run_simulation(head, input, duration, sinks);
    telemetry.close();
    std::vector<std::string> frames;
    if (render) frames = render->frames();
    const std::vector<std::string> plot_files =
        plots.write((dir.path() / "plots").string(), stats.states());
    const SummaryJson summary = make_summary(in.cfg, input, run, stats, head.hardware());
    const std::string text = summary_text(summary);
    // Input notes quote the input's text: never let a stray byte throw here,
    // after the whole run (invalid UTF-8 is written as U+FFFD).
    write_file(dir.path() / "summary.json",
               summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    write_file(dir.path() / "summary.txt", text);
    write_file(dir.path() / "index.html", html_report(summary, plot_files, frames));
    dir.commit();
    std::fputs(text.c_str(), stdout);
    std::printf("outputs in %s\n", o.out.c_str());
    return summary["result"] == "ok" ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl simulate: %s\n", e.what());
    return 2;
  }
}

}  // namespace facectl
