// The mix of several inputs steps without allocating: it runs beside the
// tick at the show rate, and a pause in it is a pause of every input.
#include <gtest/gtest.h>

#include "firmware-host/inputs/input_mix.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(InputMix, AStepAllocatesNothing) {
  const testing::TempFile f(
      "mix:\n  stale_ms: 100\n  groups:\n    mouth: { signals: [jaw_*], sources: [input] }\n"
      "  others: [live_link_face]\n");
  const FaceLayout layout({"frontalis_l", "orbicularis_oris"});
  LatestValueMailbox<FaceCommand> out;
  std::array<double, kMaxFaceSignals> neutral{};
  InputMixer mix(resolve_input_mix(parse_mix_config(ConfigNode::load_file(f.path(), "")["mix"]),
                                   layout, {MixSource::kInput, MixSource::kLiveLinkFace}, 250.0),
                 neutral, out);
  FaceCommand c;
  c.values.fill(0.5);
  mix.input(MixSource::kInput).publish(c);
  mix.input(MixSource::kLiveLinkFace).publish(c);
  testing::begin_counting_allocations();
  for (std::int64_t t = 0; t < 1000; t += 4) {
    mix.input(MixSource::kLiveLinkFace).publish(c);  // the input goes stale: a change of source
    mix.step(t * kMs);
  }
  EXPECT_EQ(testing::end_counting_allocations(), 0);
}

}  // namespace
}  // namespace facectl
