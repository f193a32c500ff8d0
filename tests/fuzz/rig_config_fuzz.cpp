// A rig file (config/rigs/*.yaml): load_rig_config against the default head's
// face layout, which its mapping terms name.
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "tests/fuzz/fuzz_support.hpp"

// The default head is loaded before fuzzing starts, so no input's time
// (-timeout) includes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  facectl::fuzz::default_head();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static facectl::fuzz::InputFile file(".yaml");
  const auto& head = facectl::fuzz::default_head().head;
  try {
    facectl::load_rig_config(file.write(data, size), head.layout);
  } catch (const facectl::ConfigError&) {  // the documented error: file:line:column
  }
  return 0;
}
