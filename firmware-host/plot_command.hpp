#pragma once

#include <string>
#include <vector>

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

struct ControllerModel;
struct TelemetryTable;
// One SVG per actuator (all if `actuators` is empty) into out_dir; returns how many.
int write_actuator_plots(const ControllerModel& m, const TelemetryTable& t,
                         const std::vector<std::string>& actuators, const std::string& out_dir);

}  // namespace facectl
