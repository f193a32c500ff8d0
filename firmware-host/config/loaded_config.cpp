#include "firmware-host/config/loaded_config.hpp"

#include <sstream>

namespace facectl {

LoadedConfig load_config(const std::string& runtime_path, const ConfigOverrides& overrides) {
  LoadedConfig cfg;
  cfg.runtime = load_runtime_config(runtime_path);
  if (overrides.rate_hz) {
    if (!(*overrides.rate_hz >= 1.0 && *overrides.rate_hz <= 10000.0)) {
      std::ostringstream e;
      e << "--rate: expected a rate in [1, 10000] Hz, found " << *overrides.rate_hz;
      throw ConfigError(e.str());
    }
    cfg.runtime.rate_hz = *overrides.rate_hz;
  }
  if (overrides.show_path) cfg.runtime.show_path = *overrides.show_path;
  if (overrides.rig_path) cfg.runtime.rig_path = *overrides.rig_path;
  if (overrides.hardware) cfg.runtime.hardware = *overrides.hardware;
  cfg.head = load_head_config(cfg.runtime.head_path);
  cfg.rig = load_rig_config(cfg.runtime.rig_path, cfg.head.layout);
  cfg.expressions = ExpressionLibrary::load(cfg.runtime.expressions_path, cfg.head.layout);
  if (!cfg.runtime.show_path.empty()) {
    cfg.show =
        Show::load(cfg.runtime.show_path, cfg.head.layout, cfg.head.neutral, cfg.expressions);
  }
  if (cfg.runtime.gamepad) resolve_gamepad_terms(*cfg.runtime.gamepad, cfg.head.layout);
  cfg.built = build_model(cfg.head, cfg.rig, cfg.runtime);
  if (!overrides.keep_problems && !cfg.built.problems.empty()) {
    std::string all;
    for (const std::string& p : cfg.built.problems) all += (all.empty() ? "" : "\n") + p;
    throw ConfigError(all + "\n(`facectl verify` checks a rig in full before power-up)");
  }
  cfg.budgets = check_bus_budgets(cfg.rig, cfg.runtime.rate_hz);
  if (!overrides.keep_problems) enforce_bus_budgets(cfg.budgets, cfg.built.warnings);
  return cfg;
}

}  // namespace facectl
