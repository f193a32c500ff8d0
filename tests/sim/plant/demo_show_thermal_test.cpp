// The shipped demo show, looped on the default rig's simulated servos, stays
// inside every servo's thermal rating and time-at-extreme budget.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/support/sim_head.hpp"

namespace facectl {
namespace {

TEST(DemoShowThermal, LoopingTheDemoShowTripsNoServo) {
  testing::SimHead head;
  ASSERT_TRUE(head.config().show.has_value());
  const Show& show = *head.config().show;
  head.send(head.model().neutral);
  head.controller().request_enable();
  std::array<double, kMaxFaceSignals> pose{};
  const double loops = 4.0;
  const double t0 = head.time();
  for (double t = 0.0; t < loops * show.duration(); t = head.time() - t0) {
    show.evaluate(std::fmod(t, show.duration()), pose);
    head.send(pose);
    head.step(head.period());
  }
  EXPECT_EQ(head.controller().state(), SafetyState::kRunning);
  double thermal = 0.0, longest = 0.0;
  for (const auto& bus : head.hardware().buses) {
    EXPECT_FALSE(bus->status().fault) << bus->name() << ": " << bus->status().reason;
    for (std::size_t i = 0; i < bus->plant_count(); ++i) {
      const sim::PlantStats& s = bus->plant(i).stats();
      EXPECT_FALSE(s.over_budget) << bus->name() << " plant " << i;
      thermal = std::max(thermal, s.thermal_peak);
      longest = std::max(longest, s.longest_at_extreme_s);
    }
  }
  std::printf("demo show x%.0f: thermal peak %.3f, longest at an extreme %.3f s\n", loops, thermal,
              longest);
  EXPECT_GT(thermal, 0.0);  // the model ran
}

}  // namespace
}  // namespace facectl
