#pragma once

#include <memory>

#include "control/controller_model.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "sim/devices/sim_hardware.hpp"

namespace facectl {

// The rig's simulated twin, from its file: each actuator's `plant:` block and
// each bus's type and speed.
std::unique_ptr<SimHardware> make_sim_hardware(const ControllerModel& model, const RigConfig& rig);

}  // namespace facectl
