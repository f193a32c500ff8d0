#include "sim/plant/servo_thermal.hpp"

#include <cmath>
#include <cstdio>

namespace facectl::sim {

ThermalModel::ThermalModel(const ThermalParams& params, const std::string& name)
    : p_(params),
      banded_(params.extreme_band > 0.0 && params.position_max > params.position_min),
      extreme_low_(params.position_min + params.extreme_band),
      extreme_high_(params.position_max - params.extreme_band),
      effort_per_error_(params.full_effort > 0.0 ? 1.0 / params.full_effort : 0.0),
      heat_scale_(1.0 / (params.rated_duty * params.rated_duty)) {
  std::snprintf(extreme_text_.data(), extreme_text_.size(),
                "thermal: %s held at an end of travel longer than its %g s budget", name.c_str(),
                p_.extreme_budget_s);
  std::snprintf(thermal_text_.data(), thermal_text_.size(),
                "thermal: %s over its continuous rating (overload protection)", name.c_str());
}

// Ticks repeat their dt: one exp per change, not per step.
void ThermalModel::set_dt(double dt) {
  alpha_dt_ = dt;
  alpha_ = 1.0 - std::exp(-dt / p_.time_constant_s);
}

void ThermalModel::trip(std::int64_t now_ns, const char* text) {
  if (fault_ == nullptr && p_.trips) fault_ = text;
  if (!stats_.over_budget) {
    stats_.over_budget = true;
    stats_.over_budget_time_s = static_cast<double>(now_ns) * 1e-9;
  }
}

}  // namespace facectl::sim
