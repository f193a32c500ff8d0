#include "firmware-host/cli/plot_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "control/units.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/report/svg_plot.hpp"
#include "firmware-host/report/telemetry_csv.hpp"

namespace facectl {
const char* state_color(std::string_view state) {
  if (state == "ENABLING") return "#3b82f6";
  if (state == "STOPPING") return "#22c55e";
  if (state == "FAULT" || state == "ESTOP") return "#ef4444";
  if (state == "IDLE") return "#9ca3af";
  return nullptr;  // RUNNING: unshaded
}

const std::array<LimitMarkRow, 4> kLimitMarkRows = {{{"position", kLimitPosition, "#7c3aed"},
                                                     {"velocity", kLimitVelocity, "#0891b2"},
                                                     {"accel.", kLimitAcceleration, "#db2777"},
                                                     {"approach", kLimitApproach, "#ea580c"}}};

Plot actuator_plot_frame(const ActuatorModel& a, double& scale, std::string& unit) {
  scale = yaml_per_si(a.kind);
  unit = yaml_unit(a.kind);
  Plot plot;
  plot.title = a.name + " (" + a.bus + ") against its limits";
  plot.x_label = "time (s)";
  plot.y_label = "position (" + unit + ")";
  plot.levels.push_back({"hardware limit", kHardLimitColor, a.limits.position_min * scale, false});
  plot.levels.push_back({"hardware limit", kHardLimitColor, a.limits.position_max * scale, false});
  plot.levels.push_back({"soft limit", kSoftLimitColor, a.limits.soft_min * scale, true});
  plot.levels.push_back({"soft limit", kSoftLimitColor, a.limits.soft_max * scale, true});
  for (const LimitMarkRow& r : kLimitMarkRows) plot.mark_rows.push_back(r.label);
  return plot;
}

namespace {

void add_state_spans(Plot& plot, const TelemetryTable& t, const std::vector<double>& time) {
  const int sc = t.find("state");
  if (sc < 0) return;
  std::size_t start = 0;
  for (std::size_t i = 1; i <= t.rows.size(); ++i) {
    const std::string& s = t.rows[start][static_cast<std::size_t>(sc)];
    if (i < t.rows.size() && t.rows[i][static_cast<std::size_t>(sc)] == s) continue;
    if (const char* color = state_color(s)) {
      plot.spans.push_back({s, color, time[start], time[i - 1]});
    }
    start = i;
  }
}

}  // namespace

int write_actuator_plots(const ControllerModel& m, const TelemetryTable& t,
                         const std::vector<std::string>& actuators, const std::string& out_dir) {
  const std::vector<double> time = t.numbers("time_s");
  std::filesystem::create_directories(out_dir);
  int written = 0;
  for (const ActuatorModel& a : m.actuators) {
    if (!actuators.empty() &&
        std::find(actuators.begin(), actuators.end(), a.name) == actuators.end()) {
      continue;
    }
    double scale = 1.0;
    std::string unit;
    Plot plot = actuator_plot_frame(a, scale, unit);
    auto to_unit = [&](std::vector<double> v) {
      for (double& x : v) x *= scale;
      return v;
    };
    plot.series.push_back({"measured", "#f59e0b", time, to_unit(t.numbers("fb." + a.name)), 1.2});
    plot.series.push_back({"command", "#1d4ed8", time, to_unit(t.numbers("cmd." + a.name)), 1.6});
    add_state_spans(plot, t, time);
    const std::vector<double> flags = t.numbers("lim." + a.name);
    for (std::size_t i = 0; i < flags.size(); ++i) {
      // Converting a double outside LimitFlags' range is undefined: refuse it.
      if (!(flags[i] >= 0.0 && flags[i] <= 65535.0) || flags[i] != std::floor(flags[i])) {
        throw ConfigError(t.file + ":" + std::to_string(i + 2) + ": column 'lim." + a.name +
                          "': expected limit flag bits (an integer 0..65535), found '" +
                          t.rows[i][static_cast<std::size_t>(t.find("lim." + a.name))] + "'");
      }
      const auto f = static_cast<LimitFlags>(flags[i]);
      for (int r = 0; r < static_cast<int>(kLimitMarkRows.size()); ++r) {
        const LimitMarkRow& row = kLimitMarkRows[static_cast<std::size_t>(r)];
        if ((f & row.bit) != 0) plot.marks.push_back({row.color, time[i], r});
      }
    }
    const std::string path = out_dir + "/" + a.name + ".svg";
    std::ofstream(path) << render_svg(plot);
    ++written;
  }
  return written;
}

int plot_command(const PlotOptions& options) {
  try {
    const LoadedConfig cfg =
        load_config(options.config.empty() ? default_config_path() : options.config);
    const TelemetryTable t = read_telemetry_csv(options.telemetry);
    const int written =
        write_actuator_plots(cfg.built.model, t, options.actuators, options.out_dir);
    if (written == 0) throw ConfigError("--actuator: expected an actuator of the rig, found none");
    std::printf("facectl plot: wrote %d plot(s) to %s\n", written, options.out_dir.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl plot: %s\n", e.what());
    return 2;
  }
}

}  // namespace facectl
