#include "sim/devices/sim_hardware.hpp"

#include "sim/devices/sim_bus_timing.hpp"

namespace facectl {

SimActuatorBus* SimHardware::find(std::string_view name) {
  for (auto& b : buses) {
    if (b->name() == name) return b.get();
  }
  return nullptr;
}

std::unique_ptr<SimHardware> make_sim_hardware(const ControllerModel& model,
                                               std::span<const SimActuatorSpec> actuators,
                                               std::span<const BusSpec> buses) {
  auto hw = std::make_unique<SimHardware>();
  std::uint64_t seed = 1;
  for (const BusModel& bus : model.buses) {
    std::vector<sim::ServoPlantParams> plants;
    std::vector<double> initial;
    std::vector<int> addresses;
    for (std::size_t i = bus.first; i < bus.first + bus.count; ++i) {
      const ActuatorModel& act = model.actuators[i];
      for (const SimActuatorSpec& a : actuators) {
        if (a.name != act.name) continue;
        sim::ServoPlantParams p = a.plant;
        p.seed = seed++;  // distinct, deterministic noise per actuator
        p.name = act.name;
        plants.push_back(p);
        initial.push_back(act.rest);
        addresses.push_back(act.address);
      }
    }
    SimBusTiming timing;
    for (const BusSpec& b : buses) {
      if (b.name == bus.name) timing = sim_bus_timing(b, addresses, model.rate_hz);
    }
    hw->buses.push_back(std::make_unique<SimActuatorBus>(bus.name, plants, initial, timing));
    hw->seams.push_back(hw->buses.back().get());
  }
  return hw;
}

}  // namespace facectl
