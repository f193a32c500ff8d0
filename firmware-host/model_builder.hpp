#pragma once

#include <string>
#include <vector>

#include "control/controller_model.hpp"
#include "firmware-host/head_config.hpp"
#include "firmware-host/rig_config.hpp"
#include "firmware-host/runtime_config.hpp"

namespace facectl {

struct BuiltModel {
  ControllerModel model;
  std::vector<std::string> warnings;  // loud notices (e.g. a widened envelope)
};

// Combines head, rig and runtime settings into the const model the tick runs
// on. Validates what no single file can (e.g. every actuator is driven).
BuiltModel build_model(const HeadConfig& head, const RigConfig& rig, const RuntimeConfig& runtime);

}  // namespace facectl
