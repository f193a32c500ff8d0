// What the control core knows of one actuator and one bus: kinds, wire encodings,
// limits. Includes nothing of facectl's, so a byte encoder or a driver can use it
// without compiling against the controller.
#pragma once

#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>

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

enum class ActuatorKind { kRotary, kLinear };

// The rig file's unit for an actuator's positions (deg or mm, and per second),
// and its factors to and from SI (rad or m): the one place that pairs them.
constexpr const char* yaml_unit(ActuatorKind k) {
  return k == ActuatorKind::kRotary ? "deg" : "mm";
}
constexpr double yaml_per_si(ActuatorKind k) {
  return k == ActuatorKind::kRotary ? 180.0 / std::numbers::pi : 1e3;
}
constexpr double si_per_yaml(ActuatorKind k) {
  return k == ActuatorKind::kRotary ? std::numbers::pi / 180.0 : 1e-3;
}

// What an actuator does when the controller faults (not on e-stop, which cuts
// everything at once): see docs/SAFETY.md, "Fault reaction".
enum class FaultReaction { kRelax, kHold, kRest };

// How positions travel on the wire: raw = round(value · scale + offset), value
// in the actuator's YAML unit (deg or mm), for command and feedback alike.
struct ActuatorEncoding {
  enum class Raw { kInt16, kUint16, kInt32 };
  Raw raw = Raw::kInt16;
  double scale = 100.0;  // counts per deg or mm
  double offset = 0.0;   // counts
};

struct ActuatorModel {
  std::string name;
  ActuatorKind kind = ActuatorKind::kRotary;
  std::string bus;
  int address = 0;
  ActuatorLimits limits;
  double rest = 0.0;  // SI
  FaultReaction fault_reaction = FaultReaction::kRelax;
  ActuatorEncoding encoding;
  double max_current_a = 0.0;  // 0 = not monitored; where the bus reports current
};

// A bus owns a contiguous slice of the actuators.
struct BusModel {
  std::string name;
  std::string type;  // "can", "modbus_rtu", "modbus_tcp"
  std::size_t first = 0;
  std::size_t count = 0;
};

}  // namespace facectl
