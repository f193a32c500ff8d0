// A per-actuator `encoding` on CiA 402 drives, end to end: a rig file whose
// drives differ in scale, sign and home offset is loaded, the real Cia402Bus
// drives simulated drives over the in-process CAN wire, and each drive gets
// the limits and targets in its own counts (checked against counts worked
// out here by hand) and reports back positions the bus reads correctly.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "drivers/can/cia402_bus.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "tests/drivers/can_test_axes.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr double kPi = 3.14159265358979323846;

// Three drives: a geared one with a home offset, one counting backwards, and
// one on the bus's default counts (131072 per rev).
const char* kRig = R"(rig:
  name: t
  buses:
    - { name: can0, type: can, interface: can0, bitrate: 1000000, protocol: cia402, rate_divider: 4 }
  actuators:
    - { name: geared, kind: rotary, bus: can0, address: 1, position_deg: { min: -30, max: 30 },
        max_velocity_deg_s: 200, max_acceleration_deg_s2: 1000, rest_deg: 0,
        map: { terms: { jaw_pitch_deg: 1 } }, encoding: { raw: int32, scale: 5000, offset: 250000 } }
    - { name: reversed, kind: rotary, bus: can0, address: 2, position_deg: { min: -30, max: 30 },
        max_velocity_deg_s: 200, max_acceleration_deg_s2: 1000, rest_deg: 0,
        map: { terms: { jaw_yaw_deg: 1 } }, encoding: { raw: int32, scale: -800, offset: -1000 } }
    - { name: plain, kind: rotary, bus: can0, address: 3, position_deg: { min: -30, max: 30 },
        max_velocity_deg_s: 200, max_acceleration_deg_s2: 1000, rest_deg: 0,
        map: { terms: { neck_pan_deg: 1 } } }
)";

RigConfig load_rig() {
  const HeadConfig head =
      load_head_config(std::string(FACECTL_SOURCE_DIR) + "/config/heads/default/head.yaml");
  testing::TempFile f(kRig);
  return load_rig_config(f.path(), head.layout);
}

TEST(Cia402Encoding, EachDriveCountsInItsOwnScaleAndOffset) {
  const RigConfig rig = load_rig();
  std::vector<ActuatorModel> axes;
  for (const ActuatorConfig& a : rig.actuators) axes.push_back(a.model);
  ASSERT_EQ(axes.size(), 3u);
  // Counts per rad and offsets, by hand from the rig text above.
  const double per_deg_to_rad = 180.0 / kPi;
  const cia402::DriveCounts geared{5000 * per_deg_to_rad, 250000};
  const cia402::DriveCounts reversed{-800 * per_deg_to_rad, -1000};
  const cia402::DriveCounts plain{131072.0 / (2 * kPi), 0};

  MemoryCanLink link{1024};
  std::vector<std::unique_ptr<sim::Cia402DriveSim>> drives;
  int node = 1;
  for (const auto& c : {geared, reversed, plain}) {
    drives.push_back(std::make_unique<sim::Cia402DriveSim>(node++, testing::fast_plant(), c, 0.0));
  }
  sim::CanDeviceNetwork net(link.devices(), {drives[0].get(), drives[1].get(), drives[2].get()});
  Cia402Bus bus("can0", link.host(), axes, std::vector<double>(3, 0.0), rig.buses[0].can);

  // The drives' own position limits (0x607D), in their counts: -30 and 30 deg.
  bus.set_enabled(true);
  std::int64_t now = 1000 * kMs;
  std::vector<double> measured(3), target(3, 0.0);
  const auto run = [&](int ticks) {
    for (int k = 0; k < ticks; ++k) {
      now += kMs;
      bus.read({now, 0.001}, measured);
      bus.write({now, 0.001}, target);
      net.poll(now);
    }
  };
  run(300);
  for (const auto& d : drives) {
    ASSERT_EQ(d->state(), cia402::DriveState::kOperationEnabled) << cia402::to_string(d->state());
  }
  EXPECT_EQ(drives[0]->limit_min(), 250000 - 150000);
  EXPECT_EQ(drives[0]->limit_max(), 250000 + 150000);
  EXPECT_EQ(drives[1]->limit_min(), -1000 - 24000);  // the ends swap with the sign
  EXPECT_EQ(drives[1]->limit_max(), -1000 + 24000);
  EXPECT_EQ(drives[2]->limit_min(), -10923);  // 131072 · -30/360, rounded
  EXPECT_EQ(drives[2]->limit_max(), 10923);

  // Each follows its target and the bus reads it back in SI.
  target = {10.0 * testing::kDeg, -12.0 * testing::kDeg, 20.0 * testing::kDeg};
  run(500);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(drives[i]->position(), target[i], 0.01 * testing::kDeg) << axes[i].name;
    EXPECT_NEAR(measured[i], target[i], 0.01 * testing::kDeg) << axes[i].name;
  }
  EXPECT_FALSE(bus.status().fault) << bus.status().reason;
}

TEST(Cia402Encoding, ADriveBuiltFromA16BitEncodingIsRefused) {
  std::vector<ActuatorModel> axes = testing::rotary_axes(1);
  axes[0].encoding = {ActuatorEncoding::Raw::kUint16, 10.0, 1500.0};
  MemoryCanLink link{16};
  try {
    Cia402Bus bus("can0", link.host(), axes, {0.0});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "bus can0: actuator axis1: a CiA 402 drive counts in raw int32, not 16 bits");
  }
}

}  // namespace
}  // namespace facectl
