#pragma once

#include <string>

#include "drivers/bus_spec.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// One entry of a rig's `buses:` list (docs/CONFIG.md, "Buses"): everything
// the real backend needs (BusSpec, which make_bus takes as it is), validated,
// and where it was written. The simulated twin only uses the name. Node and
// unit ids follow from the actuators' addresses.
struct BusConfig : BusSpec {
  std::string where;  // file:line:col of the entry

  bool is_can() const { return type == "can"; }
  bool is_modbus() const { return type == "modbus_rtu" || type == "modbus_tcp"; }
  bool is_dynamixel() const { return type == "dynamixel"; }
  bool is_feetech() const { return type == "feetech"; }
  bool is_cia402() const { return is_can() && can_protocol == "cia402"; }
  bool is_pca9685() const { return type == "pca9685"; }
  bool is_maestro() const { return type == "maestro"; }
};

// Parses and checks one `buses[]` entry. Throws ConfigError naming
// file:line:col, the key, what was expected and what was found.
BusConfig parse_bus_config(const ConfigNode& node);

}  // namespace facectl
