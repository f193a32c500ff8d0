#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace facectl::sim {

// What a simulated servo's thermal/duty model saw, for the simulation summary.
struct PlantStats {
  double time_at_extreme_s = 0;     // total time inside the extreme band
  double longest_at_extreme_s = 0;  // longest continuous stay in it
  double thermal_peak = 0;          /* 1.0 = limit */
  double duty_peak = 0;             // peak of the averaged effort, 0..1
  bool over_budget = false;         // latched: the servo faulted
  double over_budget_time_s = -1;   // clock time of the fault, -1 = never
};

// docs/CONFIG.md, "Plant": effort e = max(|command − motor| / full_effort,
// extreme_effort while inside the band) clamped to [0, 1]; duty is e averaged
// over time_constant_s, thermal is e² (heat ∝ current²) averaged the same way,
// over rated_duty² so that 1.0 is the continuous rating.
struct ThermalParams {
  double position_min = 0.0;  // the actuator's hard range, SI
  double position_max = 0.0;
  double extreme_band = 0.0;      // SI from either end; 0 = no time-at-extreme
  double extreme_budget_s = 0.0;  // continuous time in the band; 0 = no budget
  double extreme_effort = 0.8;    // effort of holding at an end of travel
  double full_effort = 0.0;       // error at full effort, SI; 0 = no effort model
  double time_constant_s = 60.0;  // of the duty and thermal averages
  double rated_duty = 0.5;        // the continuous effort the servo tolerates
  bool trips = true;              // false: statistics only, the servo never faults
  // The temperature it reports (ActuatorHealth): ambient at no heat, rated
  // at 1.0 of the continuous rating. 72 °C: the XL430-W250's default
  // Temperature Limit (ROBOTIS e-Manual, XL430-W250, control table item 31).
  double ambient_c = 25.0;
  double rated_c = 72.0;
};

class ThermalModel {
 public:
  ThermalModel(const ThermalParams& params, const std::string& name);

  // One step of `dt` seconds ending at `now_ns`; `powered` is false while the
  // drive is disabled (no effort, no holding). Inline (below): it runs for
  // every simulated servo every tick.
  void step(std::int64_t now_ns, double dt, bool powered, double output, double error);
  const PlantStats& stats() const { return stats_; }
  // What a smart servo would report of itself: temperature (°C) from the
  // heat average, load as the signed effort of the last step.
  double temperature_c() const {
    return p_.ambient_c + heat_ * heat_scale_ * (p_.rated_c - p_.ambient_c);
  }
  double load() const { return load_; }
  const char* fault() const { return fault_; }
  void clear_fault() { fault_ = nullptr; }

 private:
  void trip(std::int64_t now_ns, const char* text);
  void set_dt(double dt);  // alpha_ for a new step length

  ThermalParams p_;
  PlantStats stats_;
  double duty_ = 0.0;
  double heat_ = 0.0;  // averaged e²
  double load_ = 0.0;  // last step's effort, signed as the error
  double continuous_s_ = 0.0;
  double alpha_dt_ = -1.0;  // the dt alpha_ was computed for
  double alpha_ = 0.0;
  // Fixed by the parameters, worked out once: a step runs for every servo
  // every tick, and divisions are what it would spend its time on.
  bool banded_ = false;
  double extreme_low_ = 0.0;       // position_min + extreme_band
  double extreme_high_ = 0.0;      // position_max − extreme_band
  double effort_per_error_ = 0.0;  // 1 / full_effort, 0 = no effort model
  double heat_scale_ = 0.0;        // 1 / rated_duty²
  const char* fault_ = nullptr;
  // Written once here, so that tripping in the tick formats nothing.
  std::array<char, 128> extreme_text_{};
  std::array<char, 128> thermal_text_{};
};

inline void ThermalModel::step(std::int64_t now_ns, double dt, bool powered, double output,
                               double error) {
  if (dt <= 0.0) return;
  const bool at_extreme = powered && banded_ && (output <= extreme_low_ || output >= extreme_high_);
  bool over_time = false;  // the time-at-extreme budget is used up
  if (at_extreme) {
    continuous_s_ += dt;
    stats_.time_at_extreme_s += dt;
    stats_.longest_at_extreme_s = std::max(stats_.longest_at_extreme_s, continuous_s_);
    over_time = p_.extreme_budget_s > 0.0 && continuous_s_ > p_.extreme_budget_s;
  } else {
    continuous_s_ = 0.0;
  }

  double effort = 0.0;
  if (powered && effort_per_error_ > 0.0) effort = std::fabs(error) * effort_per_error_;
  if (at_extreme) effort = std::max(effort, p_.extreme_effort);
  effort = std::min(effort, 1.0);
  load_ = error < 0.0 ? -effort : effort;
  if (dt != alpha_dt_) set_dt(dt);
  const double alpha = alpha_;
  duty_ += alpha * (effort - duty_);
  heat_ += alpha * (effort * effort - heat_);
  const double thermal = heat_ * heat_scale_;
  stats_.duty_peak = std::max(stats_.duty_peak, duty_);
  stats_.thermal_peak = std::max(stats_.thermal_peak, thermal);

  if (over_time) {
    trip(now_ns, extreme_text_.data());
  } else if (thermal > 1.0) {
    trip(now_ns, thermal_text_.data());
  }
}

}  // namespace facectl::sim
