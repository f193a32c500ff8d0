#pragma once

#include <array>
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
};

class ThermalModel {
 public:
  ThermalModel(const ThermalParams& params, const std::string& name);

  // One step of `dt` seconds ending at `now_ns`; `powered` is false while the
  // drive is disabled (no effort, no holding).
  void step(std::int64_t now_ns, double dt, bool powered, double output, double error);
  const PlantStats& stats() const { return stats_; }
  const char* fault() const { return fault_; }
  void clear_fault() { fault_ = nullptr; }

 private:
  void trip(std::int64_t now_ns, const char* text);

  ThermalParams p_;
  PlantStats stats_;
  double duty_ = 0.0;
  double heat_ = 0.0;  // averaged e²
  double continuous_s_ = 0.0;
  double alpha_dt_ = -1.0;  // the dt alpha_ was computed for
  double alpha_ = 0.0;
  // Fixed by the parameters, worked out once: a step runs for every servo
  // every tick, and divisions are what it would spend its time on.
  bool banded_ = false;
  double effort_per_error_ = 0.0;  // 1 / full_effort, 0 = no effort model
  double heat_scale_ = 0.0;        // 1 / rated_duty²
  const char* fault_ = nullptr;
  // Written once here, so that tripping in the tick formats nothing.
  std::array<char, 128> extreme_text_{};
  std::array<char, 128> thermal_text_{};
};

}  // namespace facectl::sim
