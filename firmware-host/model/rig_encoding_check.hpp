#pragma once

#include "firmware-host/config/bus_config.hpp"
#include "firmware-host/config/rig_config.hpp"

namespace facectl {

// Checks an actuator's `encoding` against the bus that carries it, and
// resolves the bus's default when it names none (docs/CONFIG.md, "Encoding"):
// - the hardware position range must encode inside the raw type;
// - Modbus boards have one register per channel: no raw int32;
// - custom CAN `values: int16` fields are 2 bytes: no raw int32; an actuator
//   without `encoding` on a `values: int32` bus gets int32, 10000 per unit;
// - CiA 402 drives count in int32: an `encoding` there must say raw int32
//   (its scale and offset then replace the bus's counts_per_rev /
//   counts_per_mm for that drive); the range must fit strictly inside int32.
// Throws ConfigError naming the encoding's file:line:col.
void check_actuator_encoding(ActuatorConfig& actuator, const BusConfig& bus);

}  // namespace facectl
