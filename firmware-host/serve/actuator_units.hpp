#pragma once

#include <numbers>

#include "control/actuator_model.hpp"

namespace facectl {

// The API speaks the rig file's units: deg for rotary actuators, mm for linear ones.
inline double yaml_per_si(const ActuatorModel& a) {
  return a.kind == ActuatorKind::kRotary ? 180.0 / std::numbers::pi : 1000.0;
}
inline const char* yaml_unit(const ActuatorModel& a) {
  return a.kind == ActuatorKind::kRotary ? "deg" : "mm";
}

}  // namespace facectl
