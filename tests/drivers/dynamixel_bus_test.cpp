// The real DynamixelBus (a serial port, its own I/O thread) against simulated
// X-series servos on a pseudo-terminal that follow the e-Manual's control
// table and Protocol 2.0 byte for byte, and the fault matrix: a servo that
// does not answer, corrupt status packets, hardware error bits, a servo of
// another series, an echoing half-duplex adapter, a port that is not there.
#include "drivers/dynamixel/dynamixel_bus.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <thread>

#include "drivers/protocol/dynamixel2_packet.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"
#include "sim/devices/dynamixel_pty_wire.hpp"

namespace facectl {
namespace {

using namespace std::chrono_literals;
using sim::DynamixelPtyWire;
using sim::DynamixelServoSim;

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kPulsesPerDeg = 4096.0 / 360.0;

// X-series servos: 4096 pulses a turn, 2048 at 0 deg; hard limits +-90 deg.
std::vector<ActuatorModel> servos(int count) {
  std::vector<ActuatorModel> a(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    ActuatorModel& m = a[static_cast<std::size_t>(i)];
    m.name = "servo" + std::to_string(i + 1);
    m.address = i + 1;
    m.encoding = {ActuatorEncoding::Raw::kInt32, kPulsesPerDeg, 2048.0};
    m.limits.position_min = -90 * kDeg;
    m.limits.position_max = 90 * kDeg;
    m.limits.soft_min = -80 * kDeg;
    m.limits.soft_max = 80 * kDeg;
  }
  return a;
}

std::unique_ptr<DynamixelPtyWire> wire(std::vector<std::int32_t> positions,
                                       std::uint16_t model = 1060) {
  std::vector<std::unique_ptr<DynamixelServoSim>> s;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    s.push_back(
        std::make_unique<DynamixelServoSim>(static_cast<std::uint8_t>(i + 1), model, positions[i]));
  }
  return std::make_unique<DynamixelPtyWire>(std::move(s));
}

DynamixelOptions fast() {
  DynamixelOptions o;
  o.cycle_period_s = 0.004;
  o.response_timeout_s = 0.015;
  o.fault_after_s = 0.15;
  o.bus_watchdog_ms = 1000;  // a loaded test machine may stall a cycle for 100 ms
  return o;
}

// Waits for `n` more I/O cycles of the bus.
void cycles(const DynamixelBus& bus, std::uint64_t n) {
  const std::uint64_t until = bus.stats().cycles + n;
  while (bus.stats().cycles < until) std::this_thread::sleep_for(1ms);
}

bool eventually(const std::function<bool()>& ok, std::chrono::milliseconds limit = 3000ms) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (ok()) return true;
    std::this_thread::sleep_for(2ms);
  }
  return ok();
}

template <typename T>
T servo_value(DynamixelPtyWire& w, std::uint8_t id, T (DynamixelServoSim::*get)() const) {
  T v{};
  w.with_servo(id, [&](DynamixelServoSim& s) { v = (s.*get)(); });
  return v;
}

std::uint8_t servo_byte(DynamixelPtyWire& w, std::uint8_t id, std::uint16_t address) {
  std::uint8_t v = 0;
  w.with_servo(id, [&](DynamixelServoSim& s) { v = s.byte(address); });
  return v;
}

std::int32_t servo_i32(DynamixelPtyWire& w, std::uint8_t id, std::uint16_t address) {
  std::uint8_t b[4];
  for (std::uint16_t i = 0; i < 4; ++i) {
    b[i] = servo_byte(w, id, static_cast<std::uint16_t>(address + i));
  }
  return dxl_x::get_i32(b);
}

std::string reason(const DynamixelBus& bus) {
  return bus.status().reason;
}

TEST(DynamixelBus, SetsEachServoUpAndReadsWhereItIs) {
  auto w = wire({2048 + 512, 2048 - 256});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(2), {0.0, 0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  for (const std::uint8_t id : {std::uint8_t{1}, std::uint8_t{2}}) {
    EXPECT_EQ(servo_byte(*w, id, dxl_x::kReturnDelayTime), 0) << "id " << int(id);
    EXPECT_EQ(servo_byte(*w, id, dxl_x::kStatusReturnLevel), 2);
    EXPECT_EQ(servo_byte(*w, id, dxl_x::kTorqueEnable), 0);
    // The rig's hard limits, +-90 deg, as the servo's own position limits.
    EXPECT_EQ(servo_i32(*w, id, dxl_x::kMaxPositionLimit), 3072);
    EXPECT_EQ(servo_i32(*w, id, dxl_x::kMinPositionLimit), 1024);
  }
  std::vector<double> pos(2);
  ASSERT_TRUE(eventually([&] {
    bus.read({}, pos);
    return std::abs(pos[0] - 45 * kDeg) < 1e-9;
  }));
  EXPECT_NEAR(pos[1], -22.5 * kDeg, 1e-9);
  EXPECT_FALSE(bus.status().fault);
  EXPECT_GT(w->requests_of(dxl2::kSyncRead), 0U);
}

TEST(DynamixelBus, WritesTheEepromOnlyWhereItDiffers) {
  auto w = wire({2048});
  {
    DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
    ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  }
  std::uint64_t writes = 0;
  w->with_servo(1, [&](DynamixelServoSim& s) { writes = s.eeprom_writes(); });
  EXPECT_EQ(writes, 2U);  // Return Delay Time, the position limits
  DynamixelBus again("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return again.ready(); })) << reason(again);
  w->with_servo(1, [&](DynamixelServoSim& s) { EXPECT_EQ(s.eeprom_writes(), writes); });
}

TEST(DynamixelBus, EnablesBumplesslyThenFollowsTheCommands) {
  auto w = wire({2048 + 300, 2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(2), {0.0, 0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(0) && bus.torque_on(1); })) << reason(bus);
  // Torque on with the goal where the servo stood, not an older target.
  EXPECT_EQ(servo_value(*w, 1, &DynamixelServoSim::goal), 2048 + 300);
  // The Bus Watchdog, 1000 ms in 20 ms units, is armed after the torque
  // (torque_on() is true from the torque write on).
  EXPECT_TRUE(eventually([&] { return servo_byte(*w, 1, dxl_x::kBusWatchdog) == 50; }));
  EXPECT_TRUE(servo_value(*w, 1, &DynamixelServoSim::torque));
  const std::vector<double> target = {10 * kDeg, -30 * kDeg};
  bus.write({}, target);
  ASSERT_TRUE(eventually([&] {
    return servo_value(*w, 1, &DynamixelServoSim::goal) == 2048 + 114 &&
           servo_value(*w, 2, &DynamixelServoSim::goal) == 2048 - 341;
  }));
  std::vector<double> pos(2);
  ASSERT_TRUE(eventually([&] {
    bus.read({}, pos);
    return std::abs(pos[0] - 10 * kDeg) < 0.2 * kDeg && std::abs(pos[1] + 30 * kDeg) < 0.2 * kDeg;
  }));
  // A command beyond the hard limit reaches the servo clamped to its own
  // limit, which would otherwise refuse it without a word (sync write).
  bus.write({}, std::vector<double>{120 * kDeg, 0.0});
  ASSERT_TRUE(eventually([&] { return servo_value(*w, 1, &DynamixelServoSim::goal) == 3072; }));
  bus.set_enabled(false);
  ASSERT_TRUE(eventually([&] { return !servo_value(*w, 1, &DynamixelServoSim::torque); }));
  // The watchdog is cleared by the write after the torque-off one: wait for it too
  // (under ASan the test once looked between the two writes).
  EXPECT_TRUE(eventually([&] { return servo_byte(*w, 1, dxl_x::kBusWatchdog) == 0; }));
  EXPECT_FALSE(bus.status().fault) << reason(bus);
}

TEST(DynamixelBus, SwitchesTorquePerServo) {
  auto w = wire({2048, 2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(2), {0.0, 0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  std::vector<std::uint8_t> on = {0, 1};
  bus.set_actuators_enabled(on);
  EXPECT_EQ(on[0], 0);
  EXPECT_EQ(on[1], 1);  // torque is per servo: nothing else switched off
  ASSERT_TRUE(eventually([&] { return bus.torque_on(1); }));
  cycles(bus, 5);
  EXPECT_FALSE(bus.torque_on(0));
  EXPECT_FALSE(servo_value(*w, 1, &DynamixelServoSim::torque));
  EXPECT_TRUE(servo_value(*w, 2, &DynamixelServoSim::torque));
}

TEST(DynamixelBus, TurnsTorqueOffWhenItGoes) {
  auto w = wire({2048});
  {
    DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
    ASSERT_TRUE(eventually([&] { return bus.ready(); }));
    bus.set_enabled(true);
    ASSERT_TRUE(eventually([&] { return bus.torque_on(0); }));
  }
  EXPECT_TRUE(eventually([&] { return !servo_value(*w, 1, &DynamixelServoSim::torque); }));
}

TEST(DynamixelBus, ReportsTemperatureLoadAndVoltage) {
  auto w = wire({2048});
  w->with_servo(1, [](DynamixelServoSim& s) {
    s.set_temperature(61);
    s.set_load_permille(-300);
  });
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  std::vector<ActuatorHealth> h(1);
  ASSERT_TRUE(eventually([&] {
    bus.read_health(h);
    return h[0].temperature_c == 61.0;
  })) << reason(bus);
  EXPECT_DOUBLE_EQ(h[0].load, -0.3);  // XL430: Present Load in 0.1 %
  EXPECT_DOUBLE_EQ(h[0].voltage_v, 12.0);
  EXPECT_TRUE(std::isnan(h[0].current_a));
  EXPECT_EQ(h[0].hardware_error, 0U);
}

TEST(DynamixelBus, ReadsCurrentFromServosThatReportIt) {
  auto w = wire({2048}, 1020);  // XM430-W350: Present Current, 2.69 mA a count
  w->with_servo(1, [](DynamixelServoSim& s) { s.set_load_permille(100); });
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  std::vector<ActuatorHealth> h(1);
  ASSERT_TRUE(eventually([&] {
    bus.read_health(h);
    return !std::isnan(h[0].current_a);
  })) << reason(bus);
  EXPECT_NEAR(h[0].current_a, 0.269, 1e-12);
  EXPECT_TRUE(std::isnan(h[0].load));
}

// The fault matrix.

TEST(DynamixelBus, AServoThatStopsAnsweringIsAFaultNamingIt) {
  auto w = wire({2048, 2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(2), {0.0, 0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); }));
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(1); }));
  w->faults().mute_id = 2;
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus), "dxl servo 2 (servo2): not answering within 150 ms");
  EXPECT_FALSE(bus.torque_on(1));
  EXPECT_TRUE(bus.torque_on(0));
  // Back: set up again (it may have lost power) and no longer silent, but
  // its torque stays off until the controller disables and enables it: it
  // does not resume on its own.
  w->faults().mute_id = -1;
  ASSERT_TRUE(eventually([&] { return !bus.status().fault && bus.ready(); })) << reason(bus);
  cycles(bus, 10);
  EXPECT_FALSE(bus.torque_on(1));
  EXPECT_FALSE(servo_value(*w, 2, &DynamixelServoSim::torque));
  bus.set_enabled(false);
  bus.set_enabled(true);
  EXPECT_TRUE(eventually([&] { return bus.torque_on(1); })) << reason(bus);
}

TEST(DynamixelBus, ReEnablingHoldsWhereTheServoIsNotTheOldTarget) {
  auto w = wire({2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); }));
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(0); }));
  bus.write({}, std::vector<double>{20 * kDeg});
  ASSERT_TRUE(eventually([&] { return servo_value(*w, 1, &DynamixelServoSim::goal) == 2276; }));
  bus.set_enabled(false);
  ASSERT_TRUE(eventually([&] { return !servo_value(*w, 1, &DynamixelServoSim::torque); }));
  w->with_servo(1, [](DynamixelServoSim& s) { s.move_by_hand(2048 - 300); });
  cycles(bus, 3);
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(0); }));
  cycles(bus, 10);
  // No write since the enable: it holds where it was turned to.
  EXPECT_EQ(servo_value(*w, 1, &DynamixelServoSim::goal), 2048 - 300);
}

TEST(DynamixelBus, ATrippedBusWatchdogIsAFaultAndTheServoIsSwitchedOff) {
  auto w = wire({2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); }));
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(0); }));
  ASSERT_TRUE(eventually([&] { return servo_byte(*w, 1, dxl_x::kBusWatchdog) == 50; }));
  w->with_servo(1, [](DynamixelServoSim& s) { s.trip_bus_watchdog(); });
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus),
            "dxl servo 1 (servo1): its Bus Watchdog tripped (no instruction for watchdog_ms): it "
            "stopped and refuses goals");
  EXPECT_TRUE(eventually([&] { return !servo_value(*w, 1, &DynamixelServoSim::torque); }));
  // Cleared by the write after the torque's: wait for it too.
  EXPECT_TRUE(eventually([&] { return servo_byte(*w, 1, dxl_x::kBusWatchdog) == 0; }))
      << int(servo_byte(*w, 1, dxl_x::kBusWatchdog));
  EXPECT_FALSE(bus.torque_on(0));
}

TEST(DynamixelBus, ANeverAnsweringServoIsAFaultFromStartUp) {
  auto w = wire({2048});
  w->faults().mute_id = 1;
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus), "dxl servo 1 (servo1): not answering within 150 ms");
  EXPECT_FALSE(bus.ready());
}

TEST(DynamixelBus, CorruptStatusPacketsAreCountedAndDropped) {
  auto w = wire({2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); }));
  w->faults().corrupt_next = 5;
  ASSERT_TRUE(eventually([&] { return bus.stats().bad_crc >= 5; }));
  EXPECT_FALSE(bus.status().fault) << reason(bus);  // five cycles of 4 ms: not silent
  // Every status packet corrupt is a servo that does not answer.
  w->faults().corrupt_next = 1'000'000;
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus), "dxl servo 1 (servo1): not answering within 150 ms");
}

TEST(DynamixelBus, AHardwareErrorIsAFaultAndKeepsTheTorqueOff) {
  auto w = wire({2048, 2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(2), {0.0, 0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); }));
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(0); }));
  w->with_servo(1, [](DynamixelServoSim& s) {
    s.raise_hardware_error(dxl_x::kErrOverheating | dxl_x::kErrOverload);
  });
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus),
            "dxl servo 1 (servo1): hardware error: overheating (torque off; power-cycle or "
            "REBOOT the servo)");
  std::vector<ActuatorHealth> h(2);
  ASSERT_TRUE(eventually([&] {
    bus.read_health(h);
    return h[0].hardware_error != 0;
  }));
  EXPECT_EQ(h[0].hardware_error, dxl_x::kErrOverheating | dxl_x::kErrOverload);
  EXPECT_FALSE(bus.torque_on(0));
  EXPECT_TRUE(bus.torque_on(1));
  // Enabling again does not try the servo that switched itself off.
  bus.set_enabled(false);
  bus.set_enabled(true);
  cycles(bus, 10);
  EXPECT_FALSE(bus.torque_on(0));
  EXPECT_TRUE(bus.status().fault);
}

TEST(DynamixelBus, AHardwareErrorTheServoIgnoresStillSwitchesItsTorqueOff) {
  auto w = wire({2048});
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); }));
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(0); }));
  // Input voltage is not in the factory's Shutdown item: the servo stays on.
  w->with_servo(1, [](DynamixelServoSim& s) { s.raise_hardware_error(dxl_x::kErrInputVoltage); });
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus),
            "dxl servo 1 (servo1): hardware error: input voltage (torque off; power-cycle or "
            "REBOOT the servo)");
  EXPECT_TRUE(eventually([&] { return !servo_value(*w, 1, &DynamixelServoSim::torque); }));
}

TEST(DynamixelBus, RefusesAServoOfAnotherSeries) {
  auto w = wire({2048}, 2000);  // a PH42 (P series): another control table
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus),
            "dxl servo 1 (servo1): not an X-series servo (its Model Number is not one facectl "
            "knows)");
  EXPECT_FALSE(bus.ready());
}

TEST(DynamixelBus, WorksThroughAnEchoingHalfDuplexAdapter) {
  auto w = wire({2048 + 100});
  w->faults().echo = true;
  DynamixelBus bus("dxl", w->device(), 1'000'000, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  bus.set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus.torque_on(0); }));
  bus.write({}, std::vector<double>{5 * kDeg});
  EXPECT_TRUE(
      eventually([&] { return servo_value(*w, 1, &DynamixelServoSim::goal) == 2048 + 57; }));
  EXPECT_FALSE(bus.status().fault) << reason(bus);
}

TEST(DynamixelBus, APortThatIsNotThereIsAFault) {
  DynamixelBus bus("dxl", "/dev/facectl-no-such-port", 57600, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus), "dxl: serial port /dev/facectl-no-such-port lost or cannot be opened");
}

TEST(DynamixelBus, RefusesLimitsOutsideOneTurnAndDuplicateIds) {
  auto a = servos(2);
  a[0].limits.position_max = 200 * kDeg;
  try {
    DynamixelBus bus("dxl", "/dev/null", 57600, a, {0.0, 0.0}, fast());
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("actuator servo1: its hard limits are pulses 1024..4324"),
              std::string::npos)
        << e.what();
  }
  a = servos(2);
  a[1].address = 1;
  EXPECT_THROW(DynamixelBus("dxl", "/dev/null", 57600, a, {0.0, 0.0}, fast()),
               std::invalid_argument);
}

}  // namespace
}  // namespace facectl
