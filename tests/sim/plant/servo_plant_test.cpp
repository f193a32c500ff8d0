#include "sim/plant/servo_plant.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/devices/sim_actuator_bus.hpp"
#include "sim/plant/measurement_noise.hpp"

namespace facectl::sim {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(ServoPlant, HonoursItsLatencyThenMovesTowardTheCommand) {
  ServoPlantParams p;
  p.latency_s = 0.005;
  p.time_constant_s = 0.01;
  p.max_velocity = 100.0;
  ServoPlant plant(p, 0.0);
  plant.set_enabled(true);
  plant.advance(0);
  plant.command(0, 1.0);
  plant.advance(4 * kMs);
  EXPECT_DOUBLE_EQ(plant.position(), 0.0);  // still inside the latency
  plant.advance(6 * kMs);
  plant.advance(60 * kMs);
  EXPECT_NEAR(plant.position(), 1.0, 0.01);
}

TEST(ServoPlant, NeverSlewsFasterThanItsSpeedLimit) {
  ServoPlantParams p;
  p.latency_s = 0.0;
  p.time_constant_s = 0.0;  // would jump at once without the slew limit
  p.max_velocity = 2.0;
  ServoPlant plant(p, 0.0);
  plant.set_enabled(true);
  plant.advance(0);
  plant.command(0, 10.0);
  double last = 0.0;
  for (int i = 1; i <= 100; ++i) {
    plant.advance(i * kMs);
    ASSERT_LE(plant.position() - last, 2.0 * 0.001 + 1e-12);
    last = plant.position();
  }
  EXPECT_NEAR(plant.position(), 0.2, 1e-9);
}

TEST(ServoPlant, HoldsWhileDisabledAndItsNoiseIsDeterministic) {
  ServoPlantParams p;
  p.noise_stddev = 0.01;
  p.seed = 42;
  ServoPlant a(p, 0.5);
  ServoPlant b(p, 0.5);
  a.command(0, 1.0);
  a.advance(0);
  a.advance(100 * kMs);
  EXPECT_DOUBLE_EQ(a.position(), 0.5);  // disabled: did not move
  for (int i = 0; i < 10; ++i) EXPECT_DOUBLE_EQ(a.measured(), b.measured());
}

TEST(SimActuatorBus, IgnoresWritesWhileDisabledAndReportsInjectedFaults) {
  ServoPlantParams p;
  p.latency_s = 0.0;
  SimActuatorBus bus("can0", {p, p}, {0.0, 0.0});
  const double cmd[2] = {1.0, -1.0};
  bus.write({0, 0.001}, cmd);
  EXPECT_EQ(bus.writes_while_disabled(), 1u);
  EXPECT_EQ(bus.status().frames_sent, 0u);
  bus.set_enabled(true);
  bus.write({0, 0.001}, cmd);
  EXPECT_EQ(bus.status().frames_sent, 1u);
  EXPECT_FALSE(bus.status().fault);
  bus.inject_fault("bus-off");
  EXPECT_TRUE(bus.status().fault);
  EXPECT_STREQ(bus.status().reason, "bus-off");
  bus.clear_fault();
  EXPECT_FALSE(bus.status().fault);
}

}  // namespace
}  // namespace facectl::sim

namespace facectl::sim {
namespace {

TEST(MeasurementNoise, HasUnitVarianceZeroMeanBoundedTailsAndDependsOnTheSeed) {
  MeasurementNoise a(1), b(1), c(2);
  constexpr int kSamples = 200000;
  double sum = 0.0, sum_sq = 0.0, largest = 0.0;
  int beyond_two = 0, differs = 0;
  for (int i = 0; i < kSamples; ++i) {
    const double x = a.next();
    ASSERT_EQ(x, b.next());  // the same seed, the same bits
    if (x != c.next()) ++differs;
    sum += x;
    sum_sq += x * x;
    largest = std::max(largest, std::fabs(x));
    if (std::fabs(x) > 2.0) ++beyond_two;
  }
  const double mean = sum / kSamples, variance = sum_sq / kSamples - mean * mean;
  EXPECT_NEAR(mean, 0.0, 0.01);
  EXPECT_NEAR(variance, 1.0, 0.02);
  EXPECT_LE(largest, 2.0 * std::sqrt(3.0));
  // A Gaussian puts 4.55% beyond 2σ; the four-term Irwin–Hall sum about 4.0%.
  EXPECT_NEAR(static_cast<double>(beyond_two) / kSamples, 0.042, 0.006);
  EXPECT_GT(differs, kSamples - 10);
}

}  // namespace
}  // namespace facectl::sim
