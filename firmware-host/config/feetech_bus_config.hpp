#pragma once

#include "firmware-host/config/bus_config.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// The keys of a `type: feetech` bus (docs/CONFIG.md, "Feetech"). Throws
// ConfigError naming file:line:col.
void parse_feetech(const ConfigNode& node, BusConfig& bus);

}  // namespace facectl
