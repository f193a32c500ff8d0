#pragma once

#include "control/protection/drive_protection.hpp"
#include "firmware-host/config/bus_config.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// An actuator's `protection:` block (docs/CONFIG.md, "Drive-level
// protection"), against what its bus type reports: a limit on a value the
// bus cannot report is refused, naming the bus type.
DriveProtection parse_protection(const ConfigNode& node, const ActuatorModel& actuator,
                                 const BusConfig& bus);

}  // namespace facectl
