#include "control/limits/trajectory_limiter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace facectl {
namespace {

ActuatorLimits jaw_like() {
  ActuatorLimits l;
  l.position_min = -0.10;
  l.position_max = 0.35;
  l.soft_min = -0.07;
  l.soft_max = 0.31;
  l.max_velocity = 2.6;
  l.max_acceleration = 52.0;
  return l;
}

TEST(TrajectoryLimiter, SettlesExactlyOnAReachableTarget) {
  const ActuatorLimits l = jaw_like();
  LimiterState s;
  for (int i = 0; i < 2000; ++i) limit_step(l, s, 0.2, 0.001);
  EXPECT_NEAR(s.position, 0.2, 1e-12);
  EXPECT_NEAR(s.velocity, 0.0, 1e-9);
}

TEST(TrajectoryLimiter, ClampsATargetOutsideTheSoftRangeAndSaysSo) {
  const ActuatorLimits l = jaw_like();
  LimiterState s;
  std::uint8_t flags = 0;
  for (int i = 0; i < 3000; ++i) flags |= limit_step(l, s, 5.0, 0.001);
  EXPECT_NEAR(s.position, l.soft_max, 1e-12);
  EXPECT_TRUE(flags & kLimitPosition);
  EXPECT_FALSE(flags & kLimitBreach);
}

TEST(TrajectoryLimiter, ReportsVelocityAndAccelerationLimitsOnALongStep) {
  const ActuatorLimits l = jaw_like();
  LimiterState s;
  std::uint8_t flags = 0;
  double peak_v = 0.0;
  for (int i = 0; i < 1000; ++i) {
    flags |= limit_step(l, s, 0.3, 0.001);
    peak_v = std::max(peak_v, std::fabs(s.velocity));
  }
  EXPECT_TRUE(flags & kLimitVelocity);
  EXPECT_TRUE(flags & kLimitAcceleration);
  EXPECT_NEAR(peak_v, l.max_velocity, 1e-9);
}

TEST(TrajectoryLimiter, ALateTickMovesFurtherButNotFaster) {
  const ActuatorLimits l = jaw_like();
  LimiterState a;
  LimiterState b;
  for (int i = 0; i < 60; ++i) limit_step(l, a, 0.3, 0.001);  // cruising
  b = a;
  limit_step(l, a, 0.3, 0.001);
  limit_step(l, b, 0.3, 0.005);  // a tick five periods late
  EXPECT_GT(b.position - a.position, 0.0);
  EXPECT_LE(std::fabs(b.velocity), l.max_velocity * (1 + 1e-12));
}

TEST(TrajectoryLimiter, StopsBeforeTheSoftLimitEvenWhenTheTargetJumpsAway) {
  ActuatorLimits l = jaw_like();
  LimiterState s{0.0, 2.6, 0.0};  // full speed toward soft_max
  for (int i = 0; i < 1000; ++i) {
    limit_step(l, s, l.soft_max, 0.001);
    ASSERT_LE(s.position, l.soft_max + 1e-12);
  }
}

TEST(TrajectoryLimiter, StartingOutsideTheRangeOnlyMovesInward) {
  const ActuatorLimits l = jaw_like();
  LimiterState s{l.soft_max + 0.02, 0.0, 0.0};  // measured beyond the soft range at enable
  double last = s.position;
  for (int i = 0; i < 500; ++i) {
    limit_step(l, s, 10.0, 0.001);  // asks to go further out
    ASSERT_LE(s.position, last + 1e-15);
    last = s.position;
  }
  EXPECT_NEAR(s.position, l.soft_max, 1e-9);
}

TEST(TrajectoryLimiter, JerkLimitBoundsAccelerationChangesAndStillSettles) {
  ActuatorLimits l = jaw_like();
  l.max_jerk = 5000.0;
  LimiterState s;
  double prev_a = 0.0;
  int overridden = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::uint8_t f = limit_step(l, s, 0.2, 0.001);
    if ((f & kLimitJerkYielded) == 0) {
      ASSERT_LE(std::fabs(s.acceleration - prev_a), l.max_jerk * 0.001 * (1 + 1e-9)) << i;
    } else {
      ++overridden;
    }
    prev_a = s.acceleration;
  }
  EXPECT_LE(overridden, 3) << "the jerk limit should rarely need overriding on a plain step";
  EXPECT_NEAR(s.position, 0.2, 1e-6);
}

// A jerk-limited actuator caught mid-motion by a new target settles on it
// (no limit cycle), from many random states.
TEST(TrajectoryLimiter, JerkLimitedMotionSettlesFromAnyMovingState) {
  ActuatorLimits l = jaw_like();
  l.max_jerk = 2600.0;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    LimiterState s{l.soft_min + (l.soft_max - l.soft_min) * u(rng),
                   l.max_velocity * (2 * u(rng) - 1), l.max_acceleration * (2 * u(rng) - 1)};
    // Every third target sits on a soft limit, as a rest position often does.
    const double target = trial % 3 == 0   ? l.soft_min
                          : trial % 3 == 1 ? l.soft_min + (l.soft_max - l.soft_min) * u(rng)
                                           : l.soft_max;
    for (int i = 0; i < 2000; ++i) limit_step(l, s, target, 0.001);
    ASSERT_NEAR(s.position, target, 1e-6) << "trial " << trial;
    ASSERT_NEAR(s.velocity, 0.0, 1e-4) << "trial " << trial;
  }
}

// A position target is reached without passing it, from any moving state
// that can stop before it within the acceleration limit (a state already too
// fast to stop is excluded: no limiter can avoid passing then). The jerk limit
// yields near the end rather than overshoot: a jaw must not ring on a stop.
TEST(TrajectoryLimiter, ReachesATargetWithoutPassingItFromAnyMovingState) {
  for (const double jerk : {0.0, 2600.0, 500.0}) {
    ActuatorLimits l = jaw_like();
    l.max_jerk = jerk;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int tried = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      LimiterState s{l.soft_min + (l.soft_max - l.soft_min) * u(rng),
                     l.max_velocity * (2 * u(rng) - 1), l.max_acceleration * (2 * u(rng) - 1)};
      const double target = l.soft_min + (l.soft_max - l.soft_min) * u(rng);
      const double side = s.position < target ? -1.0 : 1.0;  // where it starts, from the target
      const double toward = -side * s.velocity;
      if (toward > 0.0 &&
          toward * toward / (2 * l.max_acceleration) > std::fabs(target - s.position)) {
        continue;  // cannot stop before the target even at full braking
      }
      ++tried;
      const double dt = trial % 4 == 0 ? 0.004 : 0.001;
      for (int i = 0; i < 3000; ++i) {
        limit_step(l, s, target, dt);
        ASSERT_GE(side * (s.position - target), -1e-12)
            << "jerk " << jerk << " trial " << trial << " tick " << i;
      }
      ASSERT_NEAR(s.position, target, 1e-9) << "jerk " << jerk << " trial " << trial;
    }
    EXPECT_GT(tried, 1000);
  }
}

// A stop from cruising speed passes nothing either, and the jerk limit holds on
// the way (it may yield on the last few ticks only).
TEST(TrajectoryLimiter, AJerkLimitedStopFromFullSpeedDoesNotOvershoot) {
  ActuatorLimits l = jaw_like();
  l.max_jerk = 2600.0;
  LimiterState s{l.soft_min, 0.0, 0.0};
  for (int i = 0; i < 80; ++i) limit_step(l, s, l.soft_max, 0.001);  // get moving
  ASSERT_GT(s.velocity, 2.0);
  // Room to stop at full braking, and a little more.
  const double target = s.position + 1.2 * s.velocity * s.velocity / (2 * l.max_acceleration);
  ASSERT_LT(target, l.soft_max);
  int yielded = 0;
  for (int i = 0; i < 2000; ++i) {
    if (limit_step(l, s, target, 0.001) & kLimitJerkYielded) ++yielded;
    ASSERT_LE(s.position, target + 1e-12) << i;
  }
  EXPECT_NEAR(s.position, target, 1e-9);
  EXPECT_LE(yielded, 10);
}

TEST(BrakingSpeed, StopsWithinTheDistanceUnderDiscreteBraking) {
  const double a = 50.0;
  const double dt = 0.001;
  for (double d : {1e-6, 1e-3, 0.05, 0.3}) {
    double v = braking_speed(d, a, dt);
    double x = v * dt;  // the step that used v
    while (v > 0) {
      v = std::max(0.0, v - a * dt);
      x += v * dt;
    }
    EXPECT_LE(x, d * (1 + 1e-12)) << d;
  }
}

}  // namespace
}  // namespace facectl
