// FlagTallies counts by runs (the ticks of a run added when it ends); that
// must give what counting every tick gives: per bit, the engagements (ticks
// where it rose) and the ticks it was set.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "firmware-host/simulate/simulation_stats.hpp"

namespace facectl {
namespace {

TEST(FlagTallies, RunsGiveTheCountsOfEveryTick) {
  constexpr std::size_t kBits = 6;
  std::mt19937_64 rng(4);
  for (int trial = 0; trial < 50; ++trial) {
    FlagTallies<kBits> tallies;
    std::array<Tally, kBits> expected{};
    std::uint32_t flags = 0, before = 0;
    const std::uint64_t ticks = 1 + rng() % 3000;
    for (std::uint64_t tick = 0; tick < ticks; ++tick) {
      if (rng() % 20 == 0)
        flags = static_cast<std::uint32_t>(rng() % (1u << kBits));  // rare changes
      tallies.see(flags, tick);
      for (std::size_t b = 0; b < kBits; ++b) {
        const bool set = (flags >> b & 1u) != 0, was = (before >> b & 1u) != 0;
        expected[b].ticks += set ? 1 : 0;
        expected[b].count += set && !was ? 1 : 0;
      }
      before = flags;
    }
    tallies.close(ticks);
    for (std::size_t b = 0; b < kBits; ++b) {
      EXPECT_EQ(tallies.bits[b].count, expected[b].count) << "trial " << trial << " bit " << b;
      EXPECT_EQ(tallies.bits[b].ticks, expected[b].ticks) << "trial " << trial << " bit " << b;
    }
  }
}

}  // namespace
}  // namespace facectl
