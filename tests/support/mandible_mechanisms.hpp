// The proposed mandible mechanisms of docs/MANDIBLE_MECHANISM.md, read from the
// YAML blocks of that page, so that the tested geometry is the documented one.
#pragma once

#include <cstddef>

#include "control/mapping/mandible_mechanism.hpp"

namespace facectl::testing {

// The default head's mandible axes (config/heads/default), built once.
const face::MandibleAxes& default_head_axes();

// The documented mechanism with `struts` (3: pitch, yaw, protrusion; 2: pitch,
// yaw), on the default head, over the design-default envelope, with the stroke
// limits the page suggests for its actuators.
MandibleMechanism proposed_mechanism(std::size_t struts);

}  // namespace facectl::testing
