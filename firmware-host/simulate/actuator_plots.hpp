#pragma once

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
    bool used = false;
    void see(double t, double v);
  };
  struct Track {
    std::vector<Column> command, position;
    std::vector<LimitFlags> flags;
  };
  std::size_t column_of(double t) const;

  const ControllerModel& model_;
  double duration_s_;
  std::vector<Track> tracks_;
};

}  // namespace facectl
