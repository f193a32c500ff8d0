// config/facectl.yaml, the runtime file: load_runtime_config, as `facectl` reads it.
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/runtime_config.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static facectl::fuzz::InputFile file(".yaml");
  try {
    facectl::load_runtime_config(file.write(data, size));
  } catch (const facectl::ConfigError&) {  // the documented error: file:line:column
  }
  return 0;
}
