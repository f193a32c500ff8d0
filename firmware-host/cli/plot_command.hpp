#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "control/controller_model.hpp"
#include "firmware-host/report/svg_plot.hpp"

namespace facectl {

struct PlotOptions {
  std::string telemetry;               // CSV from `facectl run --record`
  std::string config;                  // runtime config naming the rig (default: shipped)
  std::vector<std::string> actuators;  // default: all
  std::string out_dir = ".";
};

// `facectl plot`: one SVG per actuator of command and measured position
// against its soft and hard limits, with the states shaded and the ticks
// where a limit shaped the command marked. Exit 0, or 2 on unusable input.
int plot_command(const PlotOptions& options);

struct TelemetryTable;
// One SVG per actuator (all if `actuators` is empty) into out_dir; returns how many.
int write_actuator_plots(const ControllerModel& m, const TelemetryTable& t,
                         const std::vector<std::string>& actuators, const std::string& out_dir);

// The parts of an actuator's plot that do not depend on the data: title, axes,
// hardware and soft limits and the rows of limit marks. `scale` converts SI to
// `unit` (deg or mm).
Plot actuator_plot_frame(const ActuatorModel& a, double& scale, std::string& unit);

// The limiter flags marked under the plot, one row each.
struct LimitMarkRow {
  const char* label;
  LimitFlags bit;
  const char* color;
};
extern const std::array<LimitMarkRow, 4> kLimitMarkRows;

// Shading of a safety state in plots; nullptr for RUNNING (unshaded).
const char* state_color(std::string_view state);

}  // namespace facectl
