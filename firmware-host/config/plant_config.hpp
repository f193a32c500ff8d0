#pragma once

#include <optional>
#include <string>

#include "control/actuator_model.hpp"
#include "firmware-host/config/config_node.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl {

// An actuator's `plant:` block (docs/CONFIG.md, "Plant"), or its defaults
// when there is none. `unit` is "deg" or "mm", `to_si` its scale; the speed
// limit and the thermal model's band and effort scale default from `limits`.
sim::ServoPlantParams parse_plant_config(const std::optional<ConfigNode>& plant,
                                         const ActuatorLimits& limits, const std::string& unit,
                                         double to_si);

}  // namespace facectl
