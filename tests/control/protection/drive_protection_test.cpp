// Drive-level protection's step over scripted health (docs/SAFETY.md,
// "Drive-level protection"): thresholds derate then fault, noise shorter than
// the hold time does nothing, NaN is fine, and the extreme band's budget.
#include "control/protection/drive_protection.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace facectl {
namespace {

constexpr double kDt = 0.001;

ActuatorLimits limits() {
  ActuatorLimits l;
  l.position_min = -1.0;
  l.position_max = 1.0;
  l.soft_min = -0.9;
  l.soft_max = 0.9;
  l.max_velocity = 1.0;
  l.max_acceleration = 10.0;
  return l;
}

DriveProtection protection() {
  DriveProtection p;
  p.configured = true;
  p.temperature_c = {60.0, 70.0};
  p.load = {0.5, 0.9};
  p.current_a = {1.0, 2.0};
  p.voltage_min_v = 6.5;
  p.voltage_max_v = 14.0;
  p.derate_floor = 0.4;
  p.hold_s = 0.1;
  p.recover_s = 10.0;
  return p;
}

// Runs `seconds` of the same reading; true if it faulted on the way.
bool run(const DriveProtection& p, ProtectionState& s, const ActuatorHealth& h, double seconds,
         double measured = 0.0) {
  bool faulted = false;
  for (long i = 0; i < std::lround(seconds / kDt); ++i) {
    faulted = step_protection(p, limits(), h, measured, true, kDt, s) || faulted;
  }
  return faulted;
}

ActuatorHealth with(double ActuatorHealth::*field, double value) {
  ActuatorHealth h;
  h.voltage_v = 12.0;
  h.*field = value;
  return h;
}

struct Case {
  double ActuatorHealth::*field;
  double derate, mid, fault;
  ProtectionCause cause;
};

TEST(DriveProtection, EachThresholdDeratesThenFaults) {
  const DriveProtection p = protection();
  for (const Case& c :
       {Case{&ActuatorHealth::temperature_c, 60, 65, 70, ProtectionCause::kTemperature},
        Case{&ActuatorHealth::load, 0.5, 0.7, 0.9, ProtectionCause::kLoad},
        Case{&ActuatorHealth::load, -0.5, -0.7, -0.9, ProtectionCause::kLoad},
        Case{&ActuatorHealth::current_a, 1.0, 1.5, 2.0, ProtectionCause::kCurrent}}) {
    ProtectionState s;
    EXPECT_FALSE(run(p, s, with(c.field, c.derate * 0.99), 1.0));
    EXPECT_EQ(s.factor, 1.0) << "below the derate threshold";
    // Half way: the factor is half way from 1 to the floor, after the hold.
    EXPECT_FALSE(run(p, s, with(c.field, c.mid), 0.05));
    EXPECT_EQ(s.factor, 1.0) << "not yet held";
    EXPECT_FALSE(run(p, s, with(c.field, c.mid), 0.1));
    EXPECT_NEAR(s.factor, 0.7, 1e-9);
    EXPECT_EQ(s.mode, ProtectionMode::kDerating);
    // At the fault threshold: FAULT after the hold time, naming the cause.
    EXPECT_FALSE(run(p, s, with(c.field, c.fault), 0.09));
    EXPECT_NEAR(s.factor, 0.4, 1e-9);
    EXPECT_TRUE(run(p, s, with(c.field, c.fault), 0.02));
    EXPECT_EQ(s.mode, ProtectionMode::kFault);
    EXPECT_EQ(s.cause, c.cause);
    EXPECT_NEAR(s.value_at_fault, std::fabs(c.fault), 1e-12);
  }
}

TEST(DriveProtection, NoiseShorterThanTheHoldTimeDoesNothing) {
  const DriveProtection p = protection();
  ProtectionState s;
  // A 99 ms spike past the fault line every second, for ten seconds.
  for (int k = 0; k < 10; ++k) {
    EXPECT_FALSE(run(p, s, with(&ActuatorHealth::temperature_c, 95.0), 0.099));
    EXPECT_FALSE(run(p, s, with(&ActuatorHealth::temperature_c, 40.0), 0.901));
    EXPECT_EQ(s.factor, 1.0);
  }
  EXPECT_EQ(s.mode, ProtectionMode::kOk);
  // Undervoltage likewise.
  EXPECT_FALSE(run(p, s, with(&ActuatorHealth::voltage_v, 5.0), 0.099));
  EXPECT_FALSE(run(p, s, with(&ActuatorHealth::voltage_v, 12.0), 0.1));
  EXPECT_TRUE(run(p, s, with(&ActuatorHealth::voltage_v, 5.0), 0.11));
  EXPECT_EQ(s.cause, ProtectionCause::kVoltage);
}

TEST(DriveProtection, TheFactorRecoversSlowly) {
  const DriveProtection p = protection();
  ProtectionState s;
  run(p, s, with(&ActuatorHealth::temperature_c, 69.0), 0.5);
  const double low = s.factor;
  ASSERT_LT(low, 0.5);
  run(p, s, with(&ActuatorHealth::temperature_c, 30.0), 1.0);
  EXPECT_NEAR(s.factor, low + 1.0 / p.recover_s, 1e-6) << "up by 1 per recover_s";
  run(p, s, with(&ActuatorHealth::temperature_c, 30.0), 10.0);
  EXPECT_EQ(s.factor, 1.0);
  EXPECT_EQ(s.mode, ProtectionMode::kOk);
}

TEST(DriveProtection, NaNHealthWithOrWithoutLimitsIsFine) {
  ProtectionState s;
  EXPECT_FALSE(run(protection(), s, ActuatorHealth{}, 2.0));
  EXPECT_EQ(s.factor, 1.0);
  DriveProtection none;  // not configured
  EXPECT_FALSE(run(none, s, ActuatorHealth{}, 1.0));
  EXPECT_EQ(protected_target(none, limits(), 0.0, s, 0.8), 0.8);
}

TEST(DriveProtection, HardwareErrorBitsFaultAtOncePerTheMask) {
  DriveProtection p = protection();
  p.hardware_error_mask = 1u << 5;  // overload only
  ProtectionState s;
  ActuatorHealth h = with(&ActuatorHealth::temperature_c, 30.0);
  h.hardware_error = 1u << 2;
  EXPECT_FALSE(run(p, s, h, 0.5)) << "masked out";
  h.hardware_error = 1u << 5;
  EXPECT_TRUE(step_protection(p, limits(), h, 0.0, true, kDt, s)) << "on the first tick";
  EXPECT_EQ(s.cause, ProtectionCause::kHardwareError);
}

TEST(DriveProtection, DeratingPullsTowardRest) {
  const DriveProtection p = protection();
  ProtectionState s;
  s.factor = 0.5;
  EXPECT_NEAR(protected_target(p, limits(), 0.2, s, 0.8), 0.5, 1e-12);
  EXPECT_NEAR(protected_target(p, limits(), 0.2, s, -0.4), -0.1, 1e-12);
}

TEST(DriveProtection, TimeAtExtremeCoolsDownThenFaultsIfStillThere) {
  DriveProtection p = protection();
  p.extreme_band = 0.1;  // [-1, -0.9] and [0.9, 1]
  p.extreme_budget_s = 2.0;
  p.extreme_cooldown_s = 5.0;
  const ActuatorHealth ok = with(&ActuatorHealth::temperature_c, 30.0);
  ProtectionState s;
  EXPECT_FALSE(run(p, s, ok, 1.9, 0.95));
  EXPECT_EQ(s.mode, ProtectionMode::kOk);
  EXPECT_EQ(protected_target(p, limits(), 0.0, s, 0.95), 0.95);
  EXPECT_FALSE(run(p, s, ok, 0.2, 0.95));
  EXPECT_EQ(s.mode, ProtectionMode::kCooldown);
  EXPECT_EQ(protected_target(p, limits(), 0.0, s, 0.95), 0.9) << "kept out of the band";
  // It leaves the band: the cool-down runs out, then the band is open again.
  EXPECT_FALSE(run(p, s, ok, 5.0, 0.5));
  EXPECT_EQ(s.mode, ProtectionMode::kOk);
  EXPECT_EQ(protected_target(p, limits(), 0.0, s, -0.95), -0.95);
  // Over budget again, and this time it stays in the band (stuck): FAULT
  // once it has been there twice the budget.
  EXPECT_FALSE(run(p, s, ok, 3.9, -0.95));
  EXPECT_EQ(s.mode, ProtectionMode::kCooldown);
  EXPECT_TRUE(run(p, s, ok, 0.2, -0.95));
  EXPECT_EQ(s.cause, ProtectionCause::kExtreme);
}

TEST(DriveProtection, UnpoweredTimeInTheBandDoesNotCount) {
  DriveProtection p = protection();
  p.extreme_band = 0.1;
  p.extreme_budget_s = 1.0;
  p.extreme_cooldown_s = 1.0;
  ProtectionState s;
  for (int i = 0; i < 5000; ++i) {
    step_protection(p, limits(), with(&ActuatorHealth::temperature_c, 30.0), 0.95, false, kDt, s);
  }
  EXPECT_EQ(s.in_band_s, 0.0);
  EXPECT_EQ(s.mode, ProtectionMode::kOk);
}

TEST(DriveProtection, WithoutFaultsItDeratesButNeverLatches) {
  DriveProtection p = protection();
  p.faults = false;
  ProtectionState s;
  EXPECT_FALSE(run(p, s, with(&ActuatorHealth::temperature_c, 90.0), 1.0));
  EXPECT_NEAR(s.factor, 0.4, 1e-12);
  EXPECT_EQ(s.mode, ProtectionMode::kDerating);
}

}  // namespace
}  // namespace facectl
