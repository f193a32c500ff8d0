#pragma once

#include <optional>
#include <string_view>

#include "control/units.hpp"

namespace facectl {

// A mechanism between an actuator and the face part it moves, with its
// inverse. Rig mapping computes what the face part must do (the effector
// value), then the actuator position that produces it (to_actuator). Offline
// checks go the other way (to_effector). SI units throughout; no allocation.
//
//   lever         effector: cable pull (m) = radius · actuator angle (rad)
//   four_bar      actuator: input crank angle; effector: output rocker angle (rad).
//                 Pivots O2 = (0,0) and O4 = (ground, 0); crank `input`, coupler
//                 `coupler`, rocker `output`; `branch` +1/-1 picks the assembly.
//   slider_crank  effector: crank angle (rad) on a hinge (e.g. the jaw);
//                 actuator: slider position (m) along y = offset.
//                 s = r·cosθ + sqrt(l² − (r·sinθ − e)²).
struct Linkage {
  enum class Kind { kNone, kLever, kFourBar, kSliderCrank };
  Kind kind = Kind::kNone;
  double radius = 0.0;   // lever
  double ground = 0.0;   // four_bar
  double input = 0.0;    // four_bar crank, slider_crank crank
  double coupler = 0.0;  // four_bar coupler, slider_crank rod
  double output = 0.0;   // four_bar rocker
  double offset = 0.0;   // slider_crank line offset
  int branch = 1;        // four_bar assembly mode
  // Angle of the crank (slider_crank) or of the rocker (four_bar) when the
  // effector is at 0: mount the crank near 90° to the rod so that the
  // working range stays monotone and away from the dead points.
  double phase = 0.0;
  // The effector's working range. Where the inverse has two solutions (a
  // slider position reached with the crank on either side), the one in this
  // range is meant.
  double effector_min = -kPi;
  double effector_max = kPi;

  // nullopt where the mechanism cannot reach (the links cannot close).
  std::optional<double> to_actuator(double effector) const;
  std::optional<double> to_effector(double actuator) const;
};

std::string_view to_string(Linkage::Kind kind);

}  // namespace facectl
