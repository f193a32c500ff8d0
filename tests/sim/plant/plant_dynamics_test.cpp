// The plant's dynamics: deadband, backlash, acceleration limit, PD response,
// latency plus bus time, and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "sim/devices/sim_actuator_bus.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl::sim {
namespace {

constexpr std::int64_t kMs = 1'000'000;

ServoPlantParams quick() {
  ServoPlantParams p;
  p.latency_s = 0.0;
  p.time_constant_s = 0.01;
  p.max_velocity = 100.0;
  return p;
}

// A plant at 0, enabled.
ServoPlant enabled(const ServoPlantParams& p) {
  ServoPlant plant(p, 0.0);
  plant.set_enabled(true);
  return plant;
}

// Commands `command` at `from_ms`, then steps each millisecond to `until_ms`.
void run(ServoPlant& plant, double command, int from_ms, int until_ms) {
  plant.command(from_ms * kMs, command);
  for (int t = from_ms; t <= until_ms; ++t) plant.advance(t * kMs);
}

// The highest position of a 1.5 s step response to 1.0.
double step_peak(ServoPlant& plant) {
  double peak = 0.0;
  plant.command(0, 1.0);
  for (int t = 0; t <= 1500; ++t) {
    plant.advance(t * kMs);
    peak = std::max(peak, plant.position());
  }
  return peak;
}

TEST(PlantDeadband, ASmallChangeDoesNotMoveItALargerOneDoes) {
  ServoPlantParams p = quick();
  p.deadband = 0.01;
  ServoPlant plant = enabled(p);
  run(plant, 0.009, 0, 200);
  EXPECT_EQ(plant.position(), 0.0);
  run(plant, 0.5, 201, 400);
  EXPECT_GT(plant.position(), 0.5 - 0.01 - 1e-12);  // settles inside the deadband
  EXPECT_LT(plant.position(), 0.5);
}

TEST(PlantBacklash, AReversalLosesExactlyTheGapAtTheOutput) {
  ServoPlantParams p = quick();
  p.backlash = 0.02;
  ServoPlant plant = enabled(p);
  run(plant, 1.0, 0, 500);
  const double motor_top = plant.motor_position();
  const double out_top = plant.position();
  EXPECT_NEAR(motor_top - out_top, 0.01, 1e-12);  // dragged: half the gap behind
  run(plant, 0.5, 501, 1000);
  const double motor_drop = motor_top - plant.motor_position();
  const double out_drop = out_top - plant.position();
  EXPECT_NEAR(motor_drop - out_drop, 0.02, 1e-12);
}

TEST(PlantAcceleration, TheLimitIsNeverExceeded) {
  for (PlantModel model : {PlantModel::kFirstOrder, PlantModel::kPd}) {
    ServoPlantParams p = quick();
    p.model = model;
    p.natural_frequency_hz = 20;
    p.max_acceleration = 50.0;
    p.max_velocity = 5.0;
    ServoPlant plant = enabled(p);
    plant.command(0, 1.0);
    double last_v = 0.0, peak = 0.0;
    for (int t = 0; t <= 2000; ++t) {
      if (t == 600) plant.command(t * kMs, -1.0);  // a reversal mid-way
      plant.advance(t * kMs);
      peak = std::max(peak, std::fabs(plant.velocity() - last_v) / 1e-3);
      last_v = plant.velocity();
    }
    EXPECT_LE(peak, 50.0 * (1 + 1e-9));
    EXPECT_GT(peak, 49.0);  // the limit is what shaped the motion
    EXPECT_NEAR(plant.position(), -1.0, 1e-3);
  }
}

TEST(PlantPd, LowDampingOvershootsThenSettles) {
  ServoPlantParams p = quick();
  p.model = PlantModel::kPd;
  p.natural_frequency_hz = 10;
  p.damping_ratio = 0.2;
  ServoPlant plant = enabled(p);
  // Second-order step: overshoot exp(-ζπ/sqrt(1-ζ²)) = 52.7% at ζ = 0.2.
  EXPECT_NEAR(step_peak(plant) - 1.0, std::exp(-0.2 * M_PI / std::sqrt(1 - 0.04)), 0.02);
  EXPECT_NEAR(plant.position(), 1.0, 1e-3);

  p.damping_ratio = 1.0;  // critically damped: no overshoot
  ServoPlant damped = enabled(p);
  EXPECT_LE(step_peak(damped), 1.0 + 1e-9);
  EXPECT_NEAR(damped.position(), 1.0, 1e-3);
}

TEST(PlantLatency, LatencyPlusBusTimeDelaysTheFirstMotion) {
  ServoPlantParams p = quick();
  p.latency_s = 0.002;
  SimBusTiming timing;
  timing.arrival_s = {0.0, 0.0013};  // the second actuator's frame lands 1.3 ms in
  SimActuatorBus bus("b", {p, p}, {0.0, 0.0}, timing);
  bus.set_enabled(true);
  const double cmd[2] = {1.0, 1.0};
  double pos[2] = {0, 0};
  std::int64_t first_move[2] = {-1, -1};
  for (std::int64_t t = 0; t <= 10 * kMs; t += kMs / 10) {  // 10 kHz
    bus.read({t, 1e-4}, pos);
    if (t == 0) bus.write({t, 1e-4}, cmd);
    for (int i = 0; i < 2; ++i) {
      if (first_move[i] < 0 && pos[i] != 0.0) first_move[i] = t;
    }
  }
  // The step at which the command lands moves it: 2.0 ms, and 2.0 + 1.3 ms.
  EXPECT_EQ(first_move[0], 2 * kMs);
  EXPECT_EQ(first_move[1], 3 * kMs + 3 * kMs / 10);
}

std::vector<double> trace(std::uint64_t seed) {
  ServoPlantParams p = quick();
  p.model = PlantModel::kPd;
  p.deadband = 0.001;
  p.backlash = 0.004;
  p.max_acceleration = 80.0;
  p.noise_stddev = 0.001;
  p.seed = seed;
  p.thermal.position_min = -1.0;
  p.thermal.position_max = 1.0;
  p.thermal.extreme_band = 0.1;
  p.thermal.full_effort = 0.2;
  ServoPlant plant = enabled(p);
  std::vector<double> out;
  for (int t = 0; t <= 3000; ++t) {
    if (t % 7 == 0) plant.command(t * kMs, std::sin(t * 0.003));
    plant.advance(t * kMs);
    out.push_back(plant.measured());
  }
  out.push_back(plant.stats().thermal_peak);
  out.push_back(plant.stats().duty_peak);
  return out;
}

TEST(PlantDeterminism, TwoRunsGiveTheSameBits) {
  const std::vector<double> a = trace(7), b = trace(7), c = trace(8);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  EXPECT_NE(std::memcmp(a.data(), c.data(), a.size() * sizeof(double)), 0);  // the seed matters
}

}  // namespace
}  // namespace facectl::sim
