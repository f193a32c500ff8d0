// The thermal/duty model: time at an extreme against its budget, the
// thermal state against the rating, and the bus fault they raise.
#include <gtest/gtest.h>

#include <string>

#include "sim/devices/sim_actuator_bus.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl::sim {
namespace {

constexpr std::int64_t kMs = 1'000'000;

ServoPlantParams banded() {
  ServoPlantParams p;
  p.name = "jaw";
  p.latency_s = 0.0;
  p.time_constant_s = 0.01;
  p.max_velocity = 100.0;
  p.thermal.position_min = 0.0;
  p.thermal.position_max = 1.0;
  p.thermal.extreme_band = 0.05;
  p.thermal.extreme_budget_s = 2.0;
  p.thermal.full_effort = 0.1;
  p.thermal.time_constant_s = 60.0;  // slow: the budget, not the heat, trips here
  return p;
}

// Drives the bus to 0.99 (inside the band at the top) for `hold_ms`, then back
// to 0.5; returns the bus's fault text ("" when none).
std::string hold_at_extreme(SimActuatorBus& bus, int hold_ms, int total_ms) {
  bus.set_enabled(true);
  double pos[1] = {0.5};
  for (int t = 0; t <= total_ms; ++t) {
    bus.read({t * kMs, 1e-3}, pos);
    const double cmd[1] = {t < hold_ms ? 0.99 : 0.5};
    bus.write({t * kMs, 1e-3}, cmd);
  }
  return bus.status().fault ? bus.status().reason : "";
}

TEST(PlantThermal, HoldingAtAnExtremeLongerThanItsBudgetFaultsTheBus) {
  SimActuatorBus bus("servo_board", {banded()}, {0.5});
  const std::string fault = hold_at_extreme(bus, 2300, 3000);
  const PlantStats& s = bus.plant(0).stats();
  EXPECT_TRUE(s.over_budget);
  EXPECT_GT(s.longest_at_extreme_s, 2.0);
  // 0.5 → 0.99 with τ = 10 ms: inside the band (>= 0.95) from the 26 ms step,
  // over the 2 s budget 2001 steps later.
  EXPECT_NEAR(s.over_budget_time_s, 2.026, 1e-9);
  EXPECT_EQ(fault.rfind("thermal: jaw ", 0), 0u) << fault;
}

TEST(PlantThermal, HoldingShorterThanItsBudgetDoesNot) {
  SimActuatorBus bus("servo_board", {banded()}, {0.5});
  const std::string fault = hold_at_extreme(bus, 1800, 3000);
  const PlantStats& s = bus.plant(0).stats();
  EXPECT_FALSE(s.over_budget);
  EXPECT_EQ(s.over_budget_time_s, -1.0);
  EXPECT_GT(s.longest_at_extreme_s, 1.6);
  EXPECT_LT(s.longest_at_extreme_s, 2.0);
  EXPECT_NEAR(s.time_at_extreme_s, s.longest_at_extreme_s, 1e-9);  // one stay
  EXPECT_EQ(fault, "");
}

TEST(PlantThermal, SustainedEffortAboveTheRatingTripsTheThermalState) {
  ServoPlantParams p = banded();
  p.thermal.extreme_budget_s = 0.0;  // no time budget: only the heat
  p.thermal.time_constant_s = 1.0;
  p.thermal.extreme_effort = 0.8;  // 0.64 / 0.5² = 2.56 at steady state
  p.thermal.full_effort = 0.0;     // holding alone heats it
  SimActuatorBus bus("servo_board", {p}, {0.5});
  hold_at_extreme(bus, 5000, 5000);
  const PlantStats& s = bus.plant(0).stats();
  EXPECT_TRUE(s.over_budget);
  // 2.56·(1 − exp(−t/1 s)) crosses 1.0 0.495 s after it reached the band.
  EXPECT_NEAR(s.over_budget_time_s, 0.026 + 0.495, 0.002);
  EXPECT_NEAR(s.duty_peak, 0.8, 0.01);
  EXPECT_GT(s.thermal_peak, 2.5);
  EXPECT_STREQ(bus.status().reason,
               "thermal: jaw over its continuous rating (overload protection)");
}

// Holds both servos of `bus` at 0.99 for 3 s; returns the bus's fault text.
std::string hold_both_at_extreme(SimActuatorBus& bus) {
  bus.set_enabled(true);
  double pos[2] = {0.5, 0.5};
  const double cmd[2] = {0.99, 0.99};
  for (int t = 0; t <= 3000; ++t) {
    bus.read({t * kMs, 1e-3}, pos);
    bus.write({t * kMs, 1e-3}, cmd);
  }
  return bus.status().fault ? bus.status().reason : "";
}

TEST(PlantThermal, ServosTrippingOnTheSameTickFaultTheBusWithTheFirstServosName) {
  ServoPlantParams first = banded(), second = banded();
  first.name = "first";
  second.name = "second";
  SimActuatorBus bus("servo_board", {first, second}, {0.5, 0.5});
  const std::string fault = hold_both_at_extreme(bus);
  EXPECT_EQ(bus.plant(0).stats().over_budget_time_s, bus.plant(1).stats().over_budget_time_s);
  EXPECT_EQ(fault.rfind("thermal: first ", 0), 0u) << fault;
}

TEST(PlantThermal, TheBusKeepsTheFaultOfTheServoThatTrippedFirst) {
  ServoPlantParams first = banded(), second = banded();
  first.name = "first";
  second.name = "second";
  second.thermal.extreme_budget_s = 1.0;  // trips a second before `first`
  SimActuatorBus bus("servo_board", {first, second}, {0.5, 0.5});
  const std::string fault = hold_both_at_extreme(bus);
  EXPECT_TRUE(bus.plant(0).stats().over_budget);  // it tripped too, later
  EXPECT_EQ(fault.rfind("thermal: second ", 0), 0u) << fault;
}

TEST(PlantThermal, ClearingTheBusResetsTheServosLatchedFault) {
  SimActuatorBus bus("servo_board", {banded()}, {0.5});
  hold_at_extreme(bus, 2300, 3000);
  ASSERT_TRUE(bus.status().fault);
  bus.clear_fault();
  EXPECT_FALSE(bus.status().fault);
  EXPECT_TRUE(bus.plant(0).stats().over_budget);  // the record stays for the summary
}

}  // namespace
}  // namespace facectl::sim
