#pragma once

#include <optional>
#include <string>
#include <vector>

#include "firmware-host/config/config_location.hpp"  // default_config_path()
#include "firmware-host/config/expression_library.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "firmware-host/config/runtime_config.hpp"
#include "firmware-host/inputs/show.hpp"
#include "firmware-host/model/bus_budget_check.hpp"
#include "firmware-host/model/model_builder.hpp"

namespace facectl {

// Everything `facectl` reads before it may enable anything, validated as a whole.
struct LoadedConfig {
  RuntimeConfig runtime;
  HeadConfig head;
  RigConfig rig;
  ExpressionLibrary expressions;
  std::optional<Show> show;
  BuiltModel built;
  std::vector<BusBudgetResult> budgets;  // per bus, at the loop rate
};

struct ConfigOverrides {
  std::optional<std::string> show_path;
  std::optional<double> rate_hz;
  std::optional<std::string> rig_path;  // instead of the runtime file's rig
  bool keep_problems = false;           // verify reports BuiltModel::problems instead of throwing
  std::optional<HardwareMode> hardware;
};

// Loads and validates the runtime file and everything it names. Throws ConfigError.
LoadedConfig load_config(const std::string& runtime_path, const ConfigOverrides& overrides = {});

}  // namespace facectl
