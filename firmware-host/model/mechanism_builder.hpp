#pragma once

#include <string>
#include <vector>

#include "control/controller_model.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/rig_config.hpp"

namespace facectl {

// The head's mandible axes (pitch, yaw, protrusion), from its landmarks as the
// face model resolves them, so that a pose means the same to the face model,
// the mechanism and the envelope.
face::MandibleAxes load_mandible_axes(const HeadConfig& head);

// Builds the rig's mandible mechanism into m.mapping.mechanism. Needs
// m.envelope, m.actuators (controller order) and `file_order` (the controller
// index of each rig-file actuator). Throws ConfigError for what no run could
// use (unknown or rotary strut actuator, a strut with a `map`, a badly
// conditioned mechanism); appends to `problems` what makes the rig unsafe:
// actuator rest positions that are no pose of the mandible, an envelope that
// lets the face ask for a degree of freedom the mechanism holds still.
void build_mechanism(const HeadConfig& head, const RigConfig& rig,
                     const std::vector<std::size_t>& file_order, ControllerModel& m,
                     std::vector<std::string>& problems);

}  // namespace facectl
