// The trajectory limiter inside position bounds that move every tick
// (limit_step_within): as long as no bound moves past the actuator's
// committed_extreme() toward it, the trajectory never leaves the bounds and
// keeps its velocity and acceleration limits. Actuator coupled limits rest on
// this (docs/SAFETY.md, "Actuator coupled limits").
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "control/limits/trajectory_limiter.hpp"

namespace facectl {
namespace {

ActuatorLimits lip_like(double jerk) {
  // Hardware ±0.8 rad, soft ±0.7 rad, 5.2 rad/s, 70 rad/s².
  return {-0.8, 0.8, -0.7, 0.7, 5.2, 70.0, jerk};
}

TEST(LimiterMovingBounds, NeverLeavesBoundsThatKeepClearOfTheCommittedExtremes) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double jerk : {0.0, 1750.0}) {
    const ActuatorLimits l = lip_like(jerk);
    LimiterState s;
    double target = 0.0, prev_v = 0.0;
    long bounded = 0;
    for (long i = 0; i < 500'000; ++i) {
      if (u(rng) < 0.02) target = -1.0 + 2.0 * u(rng);  // steps, often beyond the soft range
      double dt = 0.001;
      if (u(rng) < 0.05) dt = 0.001 * (0.1 + 3.0 * u(rng));  // late and early ticks
      // Bounds anywhere between the committed extremes and the soft range,
      // often exactly on the extreme (the tightest the rule allows).
      const double up = committed_extreme(l, s, +1.0), down = committed_extreme(l, s, -1.0);
      const double hi = u(rng) < 0.3 ? up : up + (l.soft_max - up) * u(rng) * u(rng);
      const double lo = u(rng) < 0.3 ? down : down - (down - l.soft_min) * u(rng) * u(rng);
      ASSERT_LE(hi, l.soft_max + 1e-12) << i;
      ASSERT_GE(lo, l.soft_min - 1e-12) << i;
      const double x = s.position;
      const LimitFlags flags = limit_step_within(l, s, target, dt, lo, hi);
      bounded += (flags & kLimitCoupled) != 0;
      ASSERT_EQ(flags & kLimitBreach, 0) << i;
      ASSERT_LE(s.position, hi + 1e-12) << i;
      ASSERT_GE(s.position, lo - 1e-12) << i;
      const double v = (s.position - x) / dt;
      ASSERT_LE(std::fabs(v), l.max_velocity * (1 + 1e-9)) << i;
      ASSERT_LE(std::fabs(v - prev_v) / dt, l.max_acceleration * (1 + 1e-9) + 1e-6) << i;
      prev_v = v;
    }
    EXPECT_GT(bounded, 100'000) << "the bounds should shape many steps";
  }
}

TEST(LimiterMovingBounds, ABoundMovedInsideTheCommittedExtremeBreaksTheAccelerationLimit) {
  // The precondition is needed: at full speed toward the bound, a bound moved
  // halfway in from the committed extreme cannot be kept within max_acceleration.
  const ActuatorLimits l = lip_like(0.0);
  LimiterState s;
  for (int i = 0; i < 2000 && s.velocity < l.max_velocity; ++i) limit_step(l, s, 0.7, 0.001);
  s.position = 0.0;
  const double extreme = committed_extreme(l, s, +1.0);
  ASSERT_GT(extreme, 0.1);
  const LimitFlags ok = limit_step_within(l, s, 0.7, 0.001, l.soft_min, extreme);
  EXPECT_EQ(ok & kLimitBreach, 0);
  const double half = s.position + 0.5 * (committed_extreme(l, s, +1.0) - s.position);
  const LimitFlags broken = limit_step_within(l, s, 0.7, 0.001, l.soft_min, half);
  EXPECT_NE(broken & kLimitBreach, 0);
  EXPECT_LE(s.position, half);  // the position bound itself still holds
}

TEST(LimiterMovingBounds, CommittedExtremeIsThePositionUnlessMovingThatWay) {
  const ActuatorLimits l = lip_like(1750.0);
  const LimiterState up{0.1, 2.0, 0.0};
  const double ramp = l.max_acceleration / (2.0 * l.max_jerk);
  EXPECT_DOUBLE_EQ(committed_extreme(l, up, +1.0),
                   0.1 + 4.0 / (2.0 * l.max_acceleration) + 2.0 * ramp);
  EXPECT_DOUBLE_EQ(committed_extreme(l, up, -1.0), 0.1);
  const LimiterState down{0.1, -2.0, 0.0};
  EXPECT_DOUBLE_EQ(committed_extreme(l, down, -1.0),
                   0.1 - 4.0 / (2.0 * l.max_acceleration) - 2.0 * ramp);
  EXPECT_DOUBLE_EQ(committed_extreme(l, down, +1.0), 0.1);
}

TEST(LimiterMovingBounds, ReportsATighterBoundAsCoupledAndTheSoftRangeAsBefore) {
  const ActuatorLimits l = lip_like(0.0);
  LimiterState s;
  EXPECT_EQ(limit_step_within(l, s, 0.3, 0.001, l.soft_min, 0.2) & (kLimitCoupled | kLimitPosition),
            kLimitCoupled);
  s = {};
  EXPECT_EQ(limit_step_within(l, s, 5.0, 0.001, l.soft_min, l.soft_max) &
                (kLimitCoupled | kLimitPosition),
            kLimitPosition);
  s = {};
  EXPECT_EQ(limit_step_within(l, s, 5.0, 0.001, l.soft_min, 0.2) & (kLimitCoupled | kLimitPosition),
            kLimitCoupled | kLimitPosition);
}

}  // namespace
}  // namespace facectl
