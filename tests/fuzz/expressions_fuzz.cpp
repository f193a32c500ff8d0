// An expression library (config/expressions/*.yaml): ExpressionLibrary::load
// against the default head's face layout.
#include "firmware-host/config/expression_library.hpp"
#include "tests/fuzz/fuzz_support.hpp"

// The default head is loaded before fuzzing starts, so no input's time
// (-timeout) includes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  facectl::testing::default_head();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return facectl::fuzz::load_yaml(data, size, [](const std::string& path) {
    facectl::ExpressionLibrary::load(path, facectl::testing::default_head().head.layout);
  });
}
