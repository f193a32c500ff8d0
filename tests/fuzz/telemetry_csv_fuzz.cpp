// A telemetry CSV as `facectl run --record` writes it, read back the way
// `facectl plot` reads it: read_telemetry_csv, then write_actuator_plots for
// the first actuator of the shipped configuration's rig (its time, fb., cmd.
// and lim. columns, state spans and limit marks, drawn as an SVG).
#include <unistd.h>

#include "firmware-host/cli/plot_command.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/report/telemetry_csv.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

// The shipped configuration, loaded before fuzzing starts, so no input's time
// (-timeout) includes it.
const facectl::LoadedConfig& shipped() {
  static const facectl::LoadedConfig config = facectl::load_config(facectl::default_config_path());
  return config;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  shipped();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl;
  const LoadedConfig& config = shipped();
  static const std::vector<std::string> first = {config.built.model.actuators.at(0).name};
  static const std::string out_dir = "/tmp/facectl-fuzz-plot-" + std::to_string(::getpid());
  static fuzz::InputFile file(".csv");
  try {
    const TelemetryTable t = read_telemetry_csv(file.write(data, size));
    write_actuator_plots(config.built.model, t, first, out_dir);
  } catch (const ConfigError&) {  // the documented error: file:line and what was found
  }
  return 0;
}
