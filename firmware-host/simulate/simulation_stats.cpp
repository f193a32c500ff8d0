#include "firmware-host/simulate/simulation_stats.hpp"

#include <cmath>

namespace facectl {

SimulationStats::SimulationStats(const ControllerModel& model)
    : actuators_(model.actuators.size()) {
  states_.reserve(64);
}

void SimulationStats::add(double t, const TelemetryRecord& r, std::span<const double> positions) {
  ++ticks_;
  Actuator* const actuators = actuators_.data();  // once, not per actuator
  for (std::size_t i = 0, n = actuators_.size(); i < n; ++i) {
    Actuator& a = actuators[i];
    const double e = r.command[i] - positions[i];
    a.sum_sq += e * e;
    if (std::fabs(e) > a.max_abs) a.max_abs = std::fabs(e), a.max_at_s = t;
    a.limits.see(r.limits[i]);
  }
  face_.see(r.coupled_flags);
  actuator_.see(r.actuator_coupled_flags);
  envelope_.see(r.envelope_flags != 0 ? 1u : 0u);
  if (states_.empty() || states_.back().state != r.state) {
    if (!states_.empty()) states_.back().end_s = t;
    states_.push_back({r.state, t, t});
  }
}

void SimulationStats::finish(double t) {
  if (!states_.empty()) states_.back().end_s = t;
}

double SimulationStats::rms(std::size_t actuator) const {
  return ticks_ == 0 ? 0.0 : std::sqrt(actuators_[actuator].sum_sq / static_cast<double>(ticks_));
}

bool SimulationStats::faulted() const {
  for (const StateSpan& s : states_) {
    if (s.state == SafetyState::kFault || s.state == SafetyState::kEstop) return true;
  }
  return false;
}

}  // namespace facectl
