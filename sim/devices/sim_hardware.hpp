#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "control/controller_model.hpp"
#include "drivers/bus_spec.hpp"
#include "sim/devices/sim_actuator_bus.hpp"
#include "sim/devices/sim_safety_io.hpp"
#include "sim/plant/servo_plant.hpp"

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

// One actuator's simulated servo, as the rig file describes it.
struct SimActuatorSpec {
  std::string name;
  sim::ServoPlantParams plant;
};

// Plants start at each actuator's rest position. `actuators` and `buses` are
// matched to the model's by name; each plant gets its own noise seed, in the
// model's actuator order.
std::unique_ptr<SimHardware> make_sim_hardware(const ControllerModel& model,
                                               std::span<const SimActuatorSpec> actuators,
                                               std::span<const BusSpec> buses);

}  // namespace facectl
