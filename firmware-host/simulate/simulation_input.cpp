#include "firmware-host/simulate/simulation_input.hpp"

#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_mapping.hpp"

namespace facectl {

SimulationInput SimulationInput::load_show(const LoadedConfig& cfg, const std::string& path) {
  return from_show(Show::load(path, cfg.head.layout, cfg.head.neutral, cfg.expressions));
}

SimulationInput SimulationInput::from_show(Show show) {
  SimulationInput in;
  in.name_ = show.name();
  in.show_ = std::move(show);
  return in;
}

SimulationInput SimulationInput::load_fap(const LoadedConfig& cfg, const std::string& path) {
  const FapSequence sequence = load_fap_file(path);  // parse first: a bad file costs nothing
  SimulationInput in;
  in.fap_ = FapShow::build(sequence,
                           load_fap_mapping(cfg.head, cfg.expressions, cfg.runtime.visemes_path));
  in.name_ = in.fap_->name();
  return in;
}

}  // namespace facectl
