#include "firmware-host/simulate/simulation_input.hpp"

#include "firmware-host/inputs/recorded_input.hpp"
#include "firmware-host/inputs/text_lines.hpp"

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
  return load_input(cfg, path, InputFormat::kFap);
}

SimulationInput SimulationInput::load_input(const LoadedConfig& cfg, const std::string& path,
                                            std::optional<InputFormat> format) {
  if (!format) format = resolve_input_format(path, read_file_head(path, kDetectBytes), format);
  if (*format == InputFormat::kShow) return load_show(cfg, path);
  RecordedInput recorded = load_recorded_input(cfg, path, format);
  SimulationInput in;
  in.format_ = recorded.format;
  in.name_ = std::move(recorded.name);
  in.track_ = std::move(recorded.track);
  in.notes_ = std::move(recorded.notes);
  return in;
}

}  // namespace facectl
