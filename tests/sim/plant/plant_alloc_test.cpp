// Stepping the simulated servos, with every feature on and through a thermal
// trip, allocates nothing (the plants step inside the tick).
#include <gtest/gtest.h>

#include <cmath>

#include "sim/devices/sim_actuator_bus.hpp"
#include "tests/support/allocation_counter.hpp"

namespace facectl {
namespace {

TEST(PlantNoAllocation, SteppingEveryModelThroughAThermalTripAllocatesNothing) {
  sim::ServoPlantParams pd;
  pd.name = "jaw";
  pd.model = sim::PlantModel::kPd;
  pd.max_acceleration = 50.0;
  pd.deadband = 0.001;
  pd.backlash = 0.005;
  pd.noise_stddev = 0.001;
  pd.thermal.position_max = 1.0;
  pd.thermal.extreme_band = 0.05;
  pd.thermal.extreme_budget_s = 1.0;
  pd.thermal.full_effort = 0.1;
  sim::ServoPlantParams first_order = pd;
  first_order.model = sim::PlantModel::kFirstOrder;
  SimBusTiming timing;
  timing.arrival_s = {0.0001, 0.0002};
  SimActuatorBus bus("b", {pd, first_order}, {0.5, 0.5}, timing);
  bus.set_enabled(true);
  double pos[2] = {0, 0};
  testing::begin_counting_allocations();
  for (std::int64_t t = 0; t < 3000; ++t) {
    const double target = t < 2500 ? 0.99 : 0.5 + 0.1 * std::sin(static_cast<double>(t) * 0.01);
    const double cmd[2] = {target, target};
    bus.read({t * 1'000'000, 1e-3}, pos);
    bus.write({t * 1'000'000, 1e-3}, cmd);
    (void)bus.status();
  }
  const long allocations = testing::end_counting_allocations();
  EXPECT_TRUE(bus.status().fault);  // the trip path ran
  EXPECT_EQ(allocations, 0);
}

}  // namespace
}  // namespace facectl
