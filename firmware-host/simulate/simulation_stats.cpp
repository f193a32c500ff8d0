#include "firmware-host/simulate/simulation_stats.hpp"

#include <cmath>

namespace facectl {

SimulationStats::SimulationStats(const ControllerModel& model)
    : actuators_(model.actuators.size()),
      face_(model.face_constraints.size()),
      actuator_(model.actuator_constraints.size()) {
  states_.reserve(64);
}

void SimulationStats::add(double t, const TelemetryRecord& r, std::span<const double> positions) {
  ++ticks_;
  for (std::size_t i = 0; i < actuators_.size(); ++i) {
    Actuator& a = actuators_[i];
    const double e = r.command[i] - positions[i];
    a.sum_sq += e * e;
    if (std::fabs(e) > a.max_abs) a.max_abs = std::fabs(e), a.max_at_s = t;
    for (int b = 0; b < kLimitFlagCount; ++b) {
      a.limits[static_cast<std::size_t>(b)].see(((r.limits[i] >> b) & 1u) != 0);
    }
  }
  for (std::size_t k = 0; k < face_.size(); ++k) face_[k].see(((r.coupled_flags >> k) & 1u) != 0);
  for (std::size_t k = 0; k < actuator_.size(); ++k) {
    actuator_[k].see(((r.actuator_coupled_flags >> k) & 1u) != 0);
  }
  envelope_.see(r.envelope_flags != 0);
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
