#pragma once

#include <optional>
#include <vector>

#include "control/analysis/lp_range.hpp"
#include "control/controller_model.hpp"

namespace facectl::verify {

// What the range proof gives for one strut of the rig's mandible mechanism:
// every admissible face's stroke (before the inverse kinematics clamps it to
// the strut's soft limits) lies in [lo, hi] (m), attained at the two witness
// faces (full face vectors, jaw set to the witness pose).
struct MechanismChannel {
  std::size_t actuator = 0;
  double lo = 0.0, hi = 0.0;
  std::vector<double> at_lo, at_hi;
  bool converged = false;  // proven bounds within 1 µm of attained strokes
};

// One entry per strut; empty without a mechanism or when the admissible set
// holds no face. Coupled face limits are relaxed to the jaw by bounding their
// other terms over the box (sound: the set only grows).
std::vector<MechanismChannel> mechanism_channels(const ControllerModel& m, const Polytope& set);

}  // namespace facectl::verify
