#pragma once

#include <cstdint>

namespace facectl {

// One actuator's limits, SI units of the actuator (rad or m, and per second).
struct ActuatorLimits {
  double position_min = 0.0;  // hardware range
  double position_max = 0.0;
  double soft_min = 0.0;  // operating range, inside the hardware range
  double soft_max = 0.0;
  double max_velocity = 0.0;
  double max_acceleration = 0.0;
  double max_jerk = 0.0;  // 0 = not limited
};

// Which limit shaped an actuator's command on a tick (bit set, telemetry).
enum LimitFlag : std::uint16_t {
  kLimitPosition = 1 << 0,      // target outside the soft range: clamped
  kLimitVelocity = 1 << 1,      // max velocity capped the motion
  kLimitAcceleration = 1 << 2,  // max acceleration capped the motion
  kLimitJerk = 1 << 3,          // max jerk capped the motion
  kLimitApproach = 1 << 4,      // braking curve toward a soft limit capped the motion
  kLimitBreach = 1 << 5,        // the backstop clamped a command outside the hardware range
  kLimitInvalid = 1 << 6,       // NaN/inf target or a non-positive dt: held, not moved
  kLimitJerkYielded = 1 << 7,   // a hard bound overrode the jerk limit on this tick
  kLimitCoupled = 1 << 8,       // an actuator coupled limit's position bound shaped the step
  kLimitMapping = 1 << 9,       // the mapping held a calibration/linkage/mechanism end
};
inline constexpr int kLimitFlagCount = 10;
using LimitFlags = std::uint16_t;

}  // namespace facectl
