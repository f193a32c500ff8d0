// config/facectl.yaml, the runtime file: load_runtime_config, as `facectl` reads it.
#include "firmware-host/config/runtime_config.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return facectl::fuzz::load_yaml(
      data, size, [](const std::string& path) { facectl::load_runtime_config(path); });
}
