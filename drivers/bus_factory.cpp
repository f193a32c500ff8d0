#include "drivers/bus_factory.hpp"

#include <stdexcept>

#include "drivers/can/cia402_bus.hpp"
#include "drivers/can/custom_can_bus.hpp"
#include "drivers/can/socketcan_transport.hpp"
#include "drivers/dynamixel/dynamixel_bus.hpp"
#include "drivers/feetech/feetech_bus.hpp"
#include "drivers/i2c/i2c_dev_transport.hpp"
#include "drivers/i2c/pca9685_bus.hpp"
#include "drivers/maestro/maestro_bus.hpp"

namespace facectl {

RealBus make_bus(const BusSpec& spec, const std::vector<ActuatorModel>& actuators,
                 const std::vector<double>& initial, double tick_hz) {
  RealBus out;
  if (spec.type == "modbus_rtu" || spec.type == "modbus_tcp") {
    out.bus = std::make_unique<ModbusBus>(
        spec.name, ModbusEndpoint::parse(spec.type, spec.endpoint, spec.bitrate), actuators,
        initial, spec.modbus, spec.modbus_registers);
    return out;
  }
  if (spec.type == "dynamixel") {
    out.bus = std::make_unique<DynamixelBus>(spec.name, spec.endpoint, spec.bitrate, actuators,
                                             initial, spec.dynamixel);
    return out;
  }
  if (spec.type == "maestro") {
    out.bus = std::make_unique<MaestroBus>(spec.name, spec.endpoint, spec.bitrate, actuators,
                                           initial, spec.maestro);
    return out;
  }
  if (spec.type == "feetech") {
    out.bus = std::make_unique<FeetechBus>(spec.name, spec.endpoint, spec.bitrate, actuators,
                                           initial, spec.feetech);
    return out;
  }
  if (spec.type == "pca9685") {
    std::unique_ptr<I2cTransport> transport;
    try {
      transport = std::make_unique<I2cDevTransport>(spec.endpoint);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("bus " + spec.name + ": " + e.what());
    }
    out.bus = std::make_unique<Pca9685Bus>(spec.name, std::move(transport), actuators, initial,
                                           spec.pca9685);
    return out;
  }
  if (spec.type != "can") {
    throw std::invalid_argument("bus " + spec.name + ": unknown type '" + spec.type + "'");
  }
  if (spec.can_protocol != "cia402" && spec.can_protocol != "custom") {
    throw std::invalid_argument("bus " + spec.name + ": CAN protocol '" + spec.can_protocol +
                                "', expected cia402 or custom");
  }
  // The budget is checked before the interface is opened: a rig that cannot
  // fit is refused without touching the bus.
  CanBusBudget budget;
  {
    struct NullTransport final : CanTransport {
      bool send(const CanFrame&) override { return false; }
      bool receive(CanFrame&, CanError&) override { return false; }
    } null;
    budget =
        spec.can_protocol == "cia402"
            ? Cia402Bus(spec.name, null, actuators, initial, spec.can).budget(tick_hz, spec.bitrate)
            : CustomCanBus(spec.name, null, actuators, initial, spec.can)
                  .budget(tick_hz, spec.bitrate);
  }
  out.budget = budget.describe(spec.name);
  out.warning = budget.warned();
  if (budget.refused()) throw std::invalid_argument("bus load too high: " + out.budget);
  out.transport = std::make_unique<SocketCanTransport>(spec.endpoint, spec.can.fd);
  if (spec.can_protocol == "cia402") {
    out.bus = std::make_unique<Cia402Bus>(spec.name, *out.transport, actuators, initial, spec.can);
  } else {
    out.bus =
        std::make_unique<CustomCanBus>(spec.name, *out.transport, actuators, initial, spec.can);
  }
  return out;
}

}  // namespace facectl
