#include "firmware-host/simulate/simulation_stats.hpp"

#include <cmath>

namespace facectl {

SimulationStats::SimulationStats(const ControllerModel& model)
    : actuators_(model.actuators.size()) {
  states_.reserve(64);
}

void SimulationStats::add(double t, const TelemetryRecord& r, std::span<const double> positions) {
  const std::uint64_t tick = ticks_++;
  const std::size_t n = actuators_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double e = r.command[i] - positions[i];
    sum_sq_[i] += e * e;
    if (std::fabs(e) > max_abs_[i]) max_abs_[i] = std::fabs(e), max_at_s_[i] = t;
  }
  if (r.limits != limits_before_) {  // a limiter engaged or let go somewhere
    for (std::size_t i = 0; i < n; ++i) actuators_[i].limits.see(r.limits[i], tick);
    limits_before_ = r.limits;
  }
  face_.see(r.coupled_flags, tick);
  actuator_.see(r.actuator_coupled_flags, tick);
  envelope_.see(r.envelope_flags != 0 ? 1u : 0u, tick);
  if (states_.empty() || states_.back().state != r.state) {
    if (!states_.empty()) states_.back().end_s = t;
    states_.push_back({r.state, t, t});
  }
}

void SimulationStats::finish(double t) {
  if (!states_.empty()) states_.back().end_s = t;
  for (std::size_t i = 0; i < actuators_.size(); ++i) {
    Actuator& a = actuators_[i];
    a.sum_sq = sum_sq_[i];
    a.max_abs = max_abs_[i];
    a.max_at_s = max_at_s_[i];
    a.limits.close(ticks_);
  }
  face_.close(ticks_);
  actuator_.close(ticks_);
  envelope_.close(ticks_);
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
