// A head file (config/heads/*/head.yaml): load_head_config.
#include "firmware-host/config/head_config.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return facectl::fuzz::load_yaml(data, size,
                                  [](const std::string& path) { facectl::load_head_config(path); });
}
