#pragma once

#include <string>
#include <vector>

#include "control/controller_model.hpp"
#include "sim/plant/servo_plant.hpp"

// Shared by the CAN tests (in-process and in the QEMU guest): rotary axes on
// consecutive addresses, ±30° with 200°/s, and a fast, delay-free plant.
namespace facectl::testing {

inline constexpr double kDeg = 3.14159265358979323846 / 180.0;

inline std::vector<ActuatorModel> rotary_axes(int count) {
  std::vector<ActuatorModel> a(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    auto& m = a[static_cast<std::size_t>(i)];
    m.name = "axis" + std::to_string(i + 1);
    m.address = i + 1;
    m.limits.position_min = -30 * kDeg;
    m.limits.position_max = 30 * kDeg;
    m.limits.max_velocity = 200 * kDeg;
  }
  return a;
}

inline sim::ServoPlantParams fast_plant() {
  sim::ServoPlantParams p;
  p.time_constant_s = 0.01;
  p.latency_s = 0.0;
  p.max_velocity = 10.0;
  return p;
}

}  // namespace facectl::testing
