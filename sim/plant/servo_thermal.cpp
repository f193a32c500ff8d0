#include "sim/plant/servo_thermal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace facectl::sim {

ThermalModel::ThermalModel(const ThermalParams& params, const std::string& name)
    : p_(params),
      banded_(params.extreme_band > 0.0 && params.position_max > params.position_min),
      effort_per_error_(params.full_effort > 0.0 ? 1.0 / params.full_effort : 0.0),
      heat_scale_(1.0 / (params.rated_duty * params.rated_duty)) {
  std::snprintf(extreme_text_.data(), extreme_text_.size(),
                "thermal: %s held at an end of travel longer than its %g s budget", name.c_str(),
                p_.extreme_budget_s);
  std::snprintf(thermal_text_.data(), thermal_text_.size(),
                "thermal: %s over its continuous rating (overload protection)", name.c_str());
}

void ThermalModel::step(std::int64_t now_ns, double dt, bool powered, double output, double error) {
  if (dt <= 0.0) return;
  const bool at_extreme =
      powered && banded_ &&
      (output <= p_.position_min + p_.extreme_band || output >= p_.position_max - p_.extreme_band);
  if (at_extreme) {
    continuous_s_ += dt;
    stats_.time_at_extreme_s += dt;
    stats_.longest_at_extreme_s = std::max(stats_.longest_at_extreme_s, continuous_s_);
  } else {
    continuous_s_ = 0.0;
  }

  double effort = 0.0;
  if (powered && effort_per_error_ > 0.0) effort = std::fabs(error) * effort_per_error_;
  if (at_extreme) effort = std::max(effort, p_.extreme_effort);
  effort = std::min(effort, 1.0);
  if (dt != alpha_dt_) {  // ticks repeat their dt: one exp per change, not per step
    alpha_dt_ = dt;
    alpha_ = 1.0 - std::exp(-dt / p_.time_constant_s);
  }
  const double alpha = alpha_;
  duty_ += alpha * (effort - duty_);
  heat_ += alpha * (effort * effort - heat_);
  const double thermal = heat_ * heat_scale_;
  stats_.duty_peak = std::max(stats_.duty_peak, duty_);
  stats_.thermal_peak = std::max(stats_.thermal_peak, thermal);

  if (p_.extreme_budget_s > 0.0 && continuous_s_ > p_.extreme_budget_s) {
    trip(now_ns, extreme_text_.data());
  } else if (thermal > 1.0) {
    trip(now_ns, thermal_text_.data());
  }
}

void ThermalModel::trip(std::int64_t now_ns, const char* text) {
  if (fault_ == nullptr && p_.trips) fault_ = text;
  if (!stats_.over_budget) {
    stats_.over_budget = true;
    stats_.over_budget_time_s = static_cast<double>(now_ns) * 1e-9;
  }
}

}  // namespace facectl::sim
