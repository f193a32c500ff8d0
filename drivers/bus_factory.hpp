#pragma once

#include <memory>
#include <string>
#include <vector>

#include "control/actuator_bus.hpp"
#include "control/actuator_model.hpp"
#include "drivers/bus_spec.hpp"
#include "drivers/can/can_transport.hpp"
#include "drivers/modbus/modbus_bus.hpp"

namespace facectl {

// A real bus and what it owns. The bus is declared last so that it goes
// before the transport it talks through.
struct RealBus {
  std::unique_ptr<CanTransport> transport;  // CAN only
  std::unique_ptr<ActuatorBus> bus;
  std::string budget;    // CAN: the bus-load line, always worth printing
  bool warning = false;  // CAN: load above 50%
};

// Opens the real backend for one bus. `actuators` are the bus's slice in
// controller order; `initial` their positions until the hardware reports.
// Throws std::invalid_argument (bad spec, or a CAN load above 70%, with the
// budget line) or std::runtime_error (the interface or device cannot be
// opened), each naming the bus. Nothing is enabled here.
RealBus make_bus(const BusSpec& spec, const std::vector<ActuatorModel>& actuators,
                 const std::vector<double>& initial, double tick_hz);

}  // namespace facectl
