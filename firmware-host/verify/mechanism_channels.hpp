#pragma once

#include <vector>

#include "control/analysis/lp_range.hpp"
#include "control/controller_model.hpp"
#include "firmware-host/verify/proven_channel.hpp"

namespace facectl::verify {

// A strut of the rig's mandible mechanism: its stroke (before the inverse
// kinematics clamps it to the strut's soft limits), the witnesses with the jaw
// set to the witness pose; converged: within 1 µm of attained strokes.
using MechanismChannel = ProvenChannel;

// One entry per strut; empty without a mechanism or when the admissible set
// holds no face. Coupled face limits are relaxed to the jaw by bounding their
// other terms over the box (sound: the set only grows).
std::vector<MechanismChannel> mechanism_channels(const ControllerModel& m, const Polytope& set);

}  // namespace facectl::verify
