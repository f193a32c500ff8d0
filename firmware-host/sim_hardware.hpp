#pragma once

#include <memory>
#include <vector>

#include "control/controller_model.hpp"
#include "drivers/sim_actuator_bus.hpp"
#include "drivers/sim_safety_io.hpp"
#include "firmware-host/rig_config.hpp"

namespace facectl {

// The simulated twin of a whole rig: one SimActuatorBus per configured bus
// (its plants from each actuator's `plant:` block, its transfer times from the
// bus's type and speed at the loop rate) and the simulated safety I/O.
struct SimHardware {
  std::vector<std::unique_ptr<SimActuatorBus>> buses;
  std::vector<ActuatorBus*> seams;  // the same buses, as the controller sees them
  SimSafetyIo io;

  SimActuatorBus* find(std::string_view name);
};

// Plants start at each actuator's rest position.
std::unique_ptr<SimHardware> make_sim_hardware(const ControllerModel& model, const RigConfig& rig);

}  // namespace facectl
