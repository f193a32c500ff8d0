// The rig snippet `facectl face place-actuators` writes: the chosen actuators and the
// skin error left per expression, as YAML a person pastes into a rig.
#pragma once

#include <string>

#include "facectl/face/actuator_placement.hpp"

namespace facectl {

// `command` (the command line, lines without '#') heads the file as a comment. Numbers
// are exact (yaml_emit.hpp): read back, they equal the placement's.
std::string placement_yaml(const face::Placement& p, const std::string& command);

}  // namespace facectl
