#pragma once

#include <array>
#include <string>
#include <vector>

#include "control/actuator_model.hpp"

namespace facectl::testing {

// Hobby servos on two PCA9685 boards (0x40, 0x41), as the unit and the QEMU
// guest tests drive them: jaw on 0x40 channel 0 (600 µs + 10 per degree),
// eye on 0x40 channel 3 and brow on 0x41 channel 1 (address 18), both
// 1500 µs + 10 per degree.
inline ActuatorModel pwm_servo(const std::string& name, int address, double offset_us) {
  ActuatorModel a;
  a.name = name;
  a.kind = ActuatorKind::kRotary;
  a.address = address;
  a.encoding = {ActuatorEncoding::Raw::kUint16, 10.0, offset_us};
  return a;
}

inline std::vector<ActuatorModel> three_pwm_servos() {
  return {pwm_servo("jaw", 1, 600), pwm_servo("eye", 4, 1500), pwm_servo("brow", 18, 1500)};
}

constexpr double kPwmDeg = 3.14159265358979323846 / 180.0;
// 60°, 30°, 90°: 1200, 1800 and 2400 µs, that is 245.9, 368.85 and 491.8
// counts at 50.03 Hz (PRE_SCALE 121), worked by hand.
inline const std::array<double, 3> kThreePositions{60 * kPwmDeg, 30 * kPwmDeg, 90 * kPwmDeg};
inline constexpr std::array<int, 3> kThreeCounts{246, 369, 492};

}  // namespace facectl::testing
