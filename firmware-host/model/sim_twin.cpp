#include "firmware-host/model/sim_twin.hpp"

#include <vector>

namespace facectl {

std::unique_ptr<SimHardware> make_sim_hardware(const ControllerModel& model, const RigConfig& rig) {
  std::vector<SimActuatorSpec> actuators;
  for (const ActuatorConfig& a : rig.actuators) actuators.push_back({a.model.name, a.plant});
  const std::vector<BusSpec> buses(rig.buses.begin(), rig.buses.end());
  return make_sim_hardware(model, actuators, buses);
}

}  // namespace facectl
