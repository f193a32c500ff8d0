// A rig file (config/rigs/*.yaml): load_rig_config against the default head's
// face layout, which its mapping terms name.
#include "firmware-host/config/rig_config.hpp"
#include "tests/fuzz/fuzz_support.hpp"

// The default head is loaded before fuzzing starts, so no input's time
// (-timeout) includes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  facectl::testing::default_head();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return facectl::fuzz::load_yaml(data, size, [](const std::string& path) {
    facectl::load_rig_config(path, facectl::testing::default_head().head.layout);
  });
}
