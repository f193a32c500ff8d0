// coupled_position_bounds(): each actuator coupled limit becomes per-actuator
// position bounds whose combination is exactly the limit's slack, shared by
// demand, never inside an actuator's committed extreme.
#include "control/limits/coupled_position_bounds.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace facectl {
namespace {

struct Rig {
  std::vector<ActuatorModel> actuators;
  CoupledConstraints limits;
  std::array<LimiterState, 4> state{};
  std::array<double, 4> target{}, lo{}, hi{};

  // Four actuators with soft range [-1, 1]; limits given as (index, coeff) terms.
  explicit Rig(
      const std::vector<std::pair<std::vector<std::pair<std::size_t, double>>, double>>& ks)
      : actuators(4) {
    for (ActuatorModel& a : actuators) {
      a.limits = {-1.2, 1.2, -1.0, 1.0, 5.0, 50.0, 0.0};
    }
    for (const auto& [terms, bound] : ks) {
      CoupledConstraints::Constraint c;
      for (const auto& [i, a] : terms) {
        c.index[c.terms] = i;
        c.coeff[c.terms++] = a;
      }
      c.bound = bound;
      limits.add(c);
    }
  }
  std::uint64_t bounds() {
    lo.fill(-9.0);  // untouched unless the actuator is in a limit
    hi.fill(9.0);
    return coupled_position_bounds(limits, actuators.data(), state.data(), target.data(), lo.data(),
                                   hi.data());
  }
};

TEST(CoupledPositionBounds, SharesTheSlackByDemandAndUsesAllOfIt) {
  Rig r({{{{0, 1.0}, {1, 2.0}}, 0.6}});  // x0 + 2 x1 <= 0.6, both at 0
  r.target = {0.9, 0.3, 0.0, 0.0};       // demands 0.9 and 0.6: slack 0.6 shared 3:2
  EXPECT_EQ(r.bounds(), 0b11u);
  EXPECT_NEAR(r.hi[0], 0.36, 1e-15);
  EXPECT_NEAR(r.hi[1], 0.12, 1e-15);
  EXPECT_NEAR(r.hi[0] + 2.0 * r.hi[1], 0.6, 1e-15);
  EXPECT_EQ(r.lo[0], -1.0);  // no lower coupled bound: the soft range
  EXPECT_EQ(r.hi[2], 9.0);   // not in the limit: untouched
}

TEST(CoupledPositionBounds, GivesWhatIsLeftOverBeyondTheTargetsEqually) {
  Rig r({{{{0, 1.0}, {1, -1.0}}, 0.5}});  // x0 - x1 <= 0.5
  r.target = {0.1, 0.0, 0.0, 0.0};
  r.bounds();
  EXPECT_NEAR(r.hi[0], 0.3, 1e-15);   // demand 0.1 + half of the 0.4 spare
  EXPECT_NEAR(r.lo[1], -0.2, 1e-15);  // the other half, as a lower bound
}

TEST(CoupledPositionBounds, CountsTheBrakingDistanceOfAnActuatorMovingThatWay) {
  Rig r({{{{0, 1.0}, {1, 1.0}}, 0.5}});
  r.state[0] = {0.2, 2.0, 0.0};   // committed to 0.2 + 4/100 = 0.24
  r.state[1] = {0.1, -2.0, 0.0};  // moving away: committed to where it is
  r.target = {1.0, 1.0, 0.0, 0.0};
  r.bounds();
  const double m0 = committed_extreme(r.actuators[0].limits, r.state[0], 1.0);
  EXPECT_NEAR(m0, 0.24, 1e-15);
  EXPECT_GT(r.hi[0], m0);
  EXPECT_GT(r.hi[1], 0.1);
  EXPECT_NEAR(r.hi[0] + r.hi[1], 0.5, 1e-15);
}

TEST(CoupledPositionBounds, NobodyMovesTheSumUpFromBeyondTheLimit) {
  Rig r({{{{0, 1.0}, {1, 1.0}}, 0.5}});
  r.state[0] = {0.4, 0.0, 0.0};
  r.state[1] = {0.3, 0.0, 0.0};  // 0.7 > 0.5: started beyond it
  r.target = {1.0, -1.0, 0.0, 0.0};
  r.bounds();
  EXPECT_EQ(r.hi[0], 0.4);
  EXPECT_EQ(r.hi[1], 0.3);
  EXPECT_EQ(r.lo[1], -1.0);  // moving the sum down is free
}

TEST(CoupledPositionBounds, AnActuatorInSeveralLimitsTakesTheTightest) {
  // x0 + x1 <= 0.8 and x0 - x2 <= 0.2; x0 wants up in both.
  Rig r({{{{0, 1.0}, {1, 1.0}}, 0.8}, {{{0, 1.0}, {2, -1.0}}, 0.2}});
  r.target = {1.0, 0.0, 0.0, 0.0};
  r.bounds();
  EXPECT_NEAR(r.hi[0], 0.2, 1e-15);  // limit 1 would allow 0.8
  // The others do not want to move that way: they stay at their committed
  // extremes (limit 1's unused 0.6 is not handed on: conservative, still exact).
  EXPECT_EQ(r.hi[1], 0.0);
  EXPECT_EQ(r.lo[2], 0.0);
}

TEST(CoupledPositionBounds, AWallOutsideTheSoftRangeWinsOverIt) {
  // x0 was enabled at 1.1, above its soft max 1.0, and a limit holds it there.
  Rig r({{{{0, -1.0}}, -1.1}});  // -x0 <= -1.1: x0 >= 1.1
  r.state[0] = {1.1, 0.0, 0.0};
  r.target = {0.0, 0.0, 0.0, 0.0};
  r.bounds();
  EXPECT_EQ(r.lo[0], 1.1);
  EXPECT_EQ(r.hi[0], 1.1);
}

}  // namespace
}  // namespace facectl
