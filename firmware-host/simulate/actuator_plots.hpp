#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "control/controller_model.hpp"
#include "control/telemetry_record.hpp"
#include "firmware-host/simulate/simulation_stats.hpp"

namespace facectl {

// plots/<actuator>.svg of `facectl simulate`: per actuator the command and
// the simulated position against the hardware and soft limits, the safety
// states shaded (faults red) and the limiter marks. Gathered while the
// simulation runs, per time column (lowest, highest and their order), so a
// long show makes a plot as small as a short one and keeps every peak.
class ActuatorPlots {
 public:
  ActuatorPlots(const ControllerModel& model, double duration_s, int columns = 1600);

  // One tick at show time t (0 <= t <= duration).
  void add(double t, const TelemetryRecord& r, std::span<const double> positions);
  // Writes dir/<actuator>.svg for each actuator; returns the file names, relative to dir.
  std::vector<std::string> write(const std::string& dir,
                                 const std::vector<StateSpan>& states) const;

 private:
  struct Column {  // one series' extremes within a time column
    double lo = 0.0, hi = 0.0, t_lo = 0.0, t_hi = 0.0;
    void start(double t, double v) { lo = hi = v, t_lo = t_hi = t; }
    void see(double t, double v);
  };
  struct Cell {  // one actuator in one time column
    Column command, position;
  };
  std::size_t column_of(double t) const;

  const ControllerModel& model_;
  double duration_s_;
  std::size_t columns_, actuators_;
  // Column-major (all actuators of a column side by side), so that a tick
  // touches one contiguous row; a column's first tick starts its cells
  // instead of every tick checking whether each cell was used.
  std::vector<Cell> cells_;
  std::vector<std::array<LimitFlags, kMaxActuators>> flags_;  // per column, OR of the ticks
  std::vector<bool> used_;                                    // per column
};

}  // namespace facectl
