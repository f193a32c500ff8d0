#pragma once

#include <string>

#include "drivers/can/can_bus_options.hpp"
#include "drivers/dynamixel/dynamixel_options.hpp"
#include "drivers/feetech/feetech_options.hpp"
#include "drivers/i2c/pca9685_options.hpp"
#include "drivers/maestro/maestro_options.hpp"
#include "drivers/modbus/modbus_timing.hpp"
#include "drivers/protocol/modbus_register_map.hpp"

namespace facectl {

// What a rig's `buses[]` entry says about a real bus.
struct BusSpec {
  std::string name;
  std::string type;      // can | modbus_rtu | modbus_tcp | dynamixel | feetech | pca9685 | maestro
  std::string endpoint;  // CAN interface, serial or i2c-dev device, or host[:port]
  long bitrate = 0;      // CAN bitrate or serial baud
  std::string can_protocol = "custom";  // cia402 | custom
  CanBusOptions can;
  ModbusTiming modbus;
  modbus_map::Addresses modbus_registers;
  DynamixelOptions dynamixel;
  Pca9685Options pca9685;    // type pca9685
  MaestroOptions maestro;    // type maestro
  FeetechOptions feetech{};  // type feetech; `{}` keeps older aggregate initialisers whole
};

}  // namespace facectl
