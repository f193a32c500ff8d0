// A show (config/shows/*.yaml): Show::load against the default head and its
// expression library, then the pose at a few times, as the show player asks.
#include "firmware-host/inputs/show.hpp"
#include "tests/fuzz/fuzz_support.hpp"

// The default head is loaded before fuzzing starts, so no input's time
// (-timeout) includes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  facectl::testing::default_head();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return facectl::fuzz::load_yaml(data, size, [](const std::string& path) {
    const auto& h = facectl::testing::default_head();
    const facectl::Show show =
        facectl::Show::load(path, h.head.layout, h.head.neutral, h.expressions);
    std::array<double, facectl::kMaxFaceSignals> pose{};
    for (double u : {-1.0, 0.0, 0.25, 0.5, 1.0, 2.0}) show.evaluate(u * show.duration(), pose);
  });
}
