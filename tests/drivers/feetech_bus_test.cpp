// The real FeetechBus (a serial port, its own I/O thread) against simulated
// Feetech servos on a pseudo-terminal that follow the memory table and the
// SCS/STS protocol byte for byte, for both series (STS3215: little-endian,
// sync read; SCS0009: big-endian, one read per servo), and the fault
// matrix: a servo that does not answer, corrupt status packets, error bits
// in the status, an echoing half-duplex adapter, a port that is not there
// and a port lost while running.
#include "drivers/feetech/feetech_bus.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <thread>

#include "drivers/protocol/feetech_packet.hpp"
#include "drivers/protocol/feetech_table.hpp"
#include "sim/devices/feetech_pty_wire.hpp"

namespace facectl {
namespace {

using namespace std::chrono_literals;
using sim::FeetechPtyWire;
using sim::FeetechServoSim;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

int steps(ft::Series s) {
  return ft::steps_per_turn(s);
}
double steps_per_deg(ft::Series s) {
  return s == ft::Series::kSts ? 4096.0 / 360.0 : 1024.0 / 300.0;
}

// Centre at 0 deg; hard limits +-60 deg.
std::vector<ActuatorModel> servos(ft::Series series, int count) {
  std::vector<ActuatorModel> a(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    ActuatorModel& m = a[static_cast<std::size_t>(i)];
    m.name = "servo" + std::to_string(i + 1);
    m.address = i + 1;
    m.encoding = {ActuatorEncoding::Raw::kUint16, steps_per_deg(series), steps(series) / 2.0};
    m.limits.position_min = -60 * kDeg;
    m.limits.position_max = 60 * kDeg;
    m.limits.soft_min = -50 * kDeg;
    m.limits.soft_max = 50 * kDeg;
  }
  return a;
}

std::int32_t step_of(ft::Series s, double deg) {
  return static_cast<std::int32_t>(std::lround(deg * steps_per_deg(s) + steps(s) / 2.0));
}

FeetechOptions fast(ft::Series series) {
  FeetechOptions o;
  o.series = series;
  o.cycle_period_s = 0.004;
  o.response_timeout_s = 0.015;
  o.fault_after_s = 0.15;
  o.reconnect_interval_s = 0.05;
  return o;
}

bool eventually(const std::function<bool()>& ok, std::chrono::milliseconds limit = 3000ms) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (ok()) return true;
    std::this_thread::sleep_for(2ms);
  }
  return ok();
}

class FeetechBusTest : public ::testing::TestWithParam<ft::Series> {
 protected:
  ft::Series series() const { return GetParam(); }
  void start(std::vector<double> degrees) {
    std::vector<std::unique_ptr<FeetechServoSim>> s;
    for (std::size_t i = 0; i < degrees.size(); ++i) {
      s.push_back(std::make_unique<FeetechServoSim>(static_cast<std::uint8_t>(i + 1), series(),
                                                    step_of(series(), degrees[i])));
    }
    wire = std::make_unique<FeetechPtyWire>(std::move(s));
  }
  std::unique_ptr<FeetechBus> bus_on(std::size_t count, FeetechOptions o) {
    return std::make_unique<FeetechBus>("ft", wire->device(), 1'000'000,
                                        servos(series(), static_cast<int>(count)),
                                        std::vector<double>(count, 0.0), o);
  }
  template <typename T>
  T on(std::uint8_t id, const std::function<T(FeetechServoSim&)>& f) {
    T v{};
    wire->with_servo(id, [&](FeetechServoSim& s) { v = f(s); });
    return v;
  }
  std::uint8_t byte(std::uint8_t id, std::uint8_t address) {
    return on<std::uint8_t>(id, [&](FeetechServoSim& s) { return s.byte(address); });
  }
  int word(std::uint8_t id, std::uint8_t address) {
    return on<int>(id, [&](FeetechServoSim& s) { return s.word(address); });
  }
  bool torque(std::uint8_t id) {
    return on<bool>(id, [](FeetechServoSim& s) { return s.torque(); });
  }
  std::unique_ptr<FeetechPtyWire> wire;
};

TEST_P(FeetechBusTest, SetsEachServoUpAndReadsWhereItIs) {
  start({30.0, -20.0});
  auto bus = bus_on(2, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); })) << bus->status().reason;
  for (const std::uint8_t id : {std::uint8_t{1}, std::uint8_t{2}}) {
    EXPECT_EQ(byte(id, ft::kResponseLevel), 1) << "id " << int(id);
    EXPECT_EQ(byte(id, ft::kTorqueEnable), 0);
    EXPECT_EQ(byte(id, ft::lock_address(series())), 1) << "EEPROM locked again";
    // The rig's hard limits, +-60 deg, as the servo's own angle limits.
    EXPECT_EQ(word(id, ft::kMinAngleLimit), step_of(series(), -60));
    EXPECT_EQ(word(id, ft::kMaxAngleLimit), step_of(series(), 60));
  }
  // Written with the lock open: they survive a power cycle.
  wire->with_servo(1, [](FeetechServoSim& s) { s.power_cycle(); });
  EXPECT_EQ(word(1, ft::kMaxAngleLimit), step_of(series(), 60));
  std::vector<double> pos(2);
  const double tol = 0.6 / steps_per_deg(series()) * kDeg;
  ASSERT_TRUE(eventually([&] {
    bus->read({}, pos);
    return std::abs(pos[0] - 30 * kDeg) < tol && std::abs(pos[1] + 20 * kDeg) < tol;
  })) << pos[0] / kDeg
      << " " << pos[1] / kDeg;
  // STS reads by sync read; SCS, which lacks it, one read per servo.
  if (series() == ft::Series::kSts) {
    EXPECT_GT(wire->requests_of(scs::kSyncRead), 0u);
  } else {
    EXPECT_EQ(wire->requests_of(scs::kSyncRead), 0u);
  }
}

TEST_P(FeetechBusTest, WritesTheEepromOnlyWhereItDiffers) {
  start({0.0});
  {
    auto bus = bus_on(1, fast(series()));
    ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  }
  const auto writes = on<std::uint64_t>(1, [](FeetechServoSim& s) { return s.eeprom_writes(); });
  EXPECT_GT(writes, 0u);
  auto bus = bus_on(1, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  EXPECT_EQ(on<std::uint64_t>(1, [](FeetechServoSim& s) { return s.eeprom_writes(); }), writes);
}

TEST_P(FeetechBusTest, EnablesBumplesslyThenFollowsTheCommandsPerServo) {
  start({10.0, -10.0});
  auto bus = bus_on(2, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  std::uint8_t flags[2] = {1, 0};
  bus->set_actuators_enabled(flags);
  ASSERT_TRUE(eventually([&] { return bus->torque_on(0) && torque(1); }));
  EXPECT_FALSE(torque(2));
  // Bumpless: the goal is where it stood, not the 0 written before enable.
  EXPECT_EQ(word(1, ft::kGoalPosition), step_of(series(), 10));
  const std::vector<double> cmd = {25 * kDeg, 0.0};
  bus->write({}, cmd);
  ASSERT_TRUE(eventually([&] { return word(1, ft::kGoalPosition) == step_of(series(), 25); }))
      << word(1, ft::kGoalPosition);
  EXPECT_GT(wire->requests_of(scs::kSyncWrite), 0u);
  // Beyond the hard limit: clamped to it.
  const std::vector<double> far = {80 * kDeg, 0.0};
  bus->write({}, far);
  ASSERT_TRUE(eventually([&] { return word(1, ft::kGoalPosition) == step_of(series(), 60); }));
  bus->set_enabled(false);
  ASSERT_TRUE(eventually([&] { return !torque(1); }));
}

TEST_P(FeetechBusTest, ReportsTemperatureLoadVoltageAndErrorBits) {
  start({0.0});
  auto bus = bus_on(1, fast(series()));
  wire->with_servo(1, [](FeetechServoSim& s) {
    s.set_temperature(41);
    s.set_load_permille(-250);
  });
  ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  ActuatorHealth h[1];
  ASSERT_TRUE(eventually([&] {
    bus->read_health(h);
    return h[0].temperature_c == 41.0;
  }));
  EXPECT_DOUBLE_EQ(h[0].load, -0.25);
  EXPECT_NEAR(h[0].voltage_v, 7.4, 1e-9);
  EXPECT_EQ(h[0].hardware_error, 0u);
}

TEST_P(FeetechBusTest, AnErrorStatusSwitchesTorqueOffUntilClearedAndReEnabled) {
  start({0.0});
  auto bus = bus_on(1, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  bus->set_enabled(true);
  ASSERT_TRUE(eventually([&] { return torque(1); }));
  // Angle sensor: a flag the servo does not unload for; the bus does.
  wire->with_servo(1, [](FeetechServoSim& s) { s.raise_error(ft::kErrAngle); });
  ASSERT_TRUE(eventually([&] { return bus->status().fault; }));
  EXPECT_EQ(std::string(bus->status().reason),
            "ft servo 1 (servo1): error status: angle sensor (torque off until it clears and "
            "the controller enables again)");
  ASSERT_TRUE(eventually([&] { return !torque(1); }));
  // The feedback is published at the end of the cycle that found the bits.
  ActuatorHealth h[1];
  EXPECT_TRUE(eventually([&] {
    bus->read_health(h);
    return h[0].hardware_error == ft::kErrAngle;
  })) << h[0].hardware_error;
  // Cleared: no fault, but torque stays off while the controller still enables.
  wire->with_servo(1, [](FeetechServoSim& s) { s.raise_error(0); });
  ASSERT_TRUE(eventually([&] { return !bus->status().fault; }));
  std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(torque(1)) << "latched off";
  bus->set_enabled(false);
  bus->set_enabled(true);
  EXPECT_TRUE(eventually([&] { return torque(1); }));
}

TEST_P(FeetechBusTest, AServoThatStopsAnsweringIsAFaultNamingIt) {
  start({0.0, 0.0});
  auto bus = bus_on(2, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  bus->set_enabled(true);
  ASSERT_TRUE(eventually([&] { return bus->torque_on(1); }));
  wire->faults().mute_id = 2;
  ASSERT_TRUE(eventually([&] { return bus->status().fault; }));
  EXPECT_EQ(std::string(bus->status().reason), "ft servo 2 (servo2): not answering within 150 ms");
  EXPECT_FALSE(bus->torque_on(1));
  EXPECT_TRUE(bus->torque_on(0)) << "the other servo goes on";
  wire->faults().mute_id = -1;
  ASSERT_TRUE(eventually([&] { return !bus->status().fault && bus->ready(); }));
  std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(bus->torque_on(1)) << "latched until the controller disables";
}

TEST_P(FeetechBusTest, CorruptStatusPacketsAreCountedAndDropped) {
  start({0.0});
  auto bus = bus_on(1, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  wire->faults().corrupt_next = 3;
  ASSERT_TRUE(eventually([&] { return bus->stats().bad_checksum >= 3; }));
  std::this_thread::sleep_for(30ms);
  EXPECT_FALSE(bus->status().fault) << bus->status().reason;
  EXPECT_GE(bus->status().errors, 3u);
}

TEST_P(FeetechBusTest, WorksThroughAnEchoingHalfDuplexAdapter) {
  start({15.0});
  wire->faults().echo = true;
  auto bus = bus_on(1, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); })) << bus->status().reason;
  bus->set_enabled(true);
  const std::vector<double> cmd = {-5 * kDeg};
  bus->write({}, cmd);
  EXPECT_TRUE(eventually([&] { return word(1, ft::kGoalPosition) == step_of(series(), -5); }));
}

TEST_P(FeetechBusTest, APortLostWhileRunningIsAFault) {
  start({0.0});
  auto bus = bus_on(1, fast(series()));
  ASSERT_TRUE(eventually([&] { return bus->ready(); }));
  const std::string device = wire->device();
  wire.reset();  // the pty goes away, as an unplugged adapter
  ASSERT_TRUE(eventually([&] { return bus->status().fault; }));
  EXPECT_FALSE(bus->ready());
}

INSTANTIATE_TEST_SUITE_P(Series, FeetechBusTest,
                         ::testing::Values(ft::Series::kSts, ft::Series::kScs),
                         [](const auto& p) { return p.param == ft::Series::kSts ? "Sts" : "Scs"; });

TEST(FeetechBus, APortThatIsNotThereIsAFault) {
  FeetechBus bus("ft", "/dev/facectl-no-such-port", 1'000'000, servos(ft::Series::kSts, 1), {0.0},
                 fast(ft::Series::kSts));
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(std::string(bus.status().reason),
            "ft: serial port /dev/facectl-no-such-port lost or cannot be opened");
}

TEST(FeetechBus, RefusesLimitsOutsideTheSeriesAndDuplicateIds) {
  auto a = servos(ft::Series::kScs, 2);
  a[1].address = 1;
  EXPECT_THROW(FeetechBus("ft", "/dev/null", 1'000'000, a, {0.0, 0.0}, fast(ft::Series::kScs)),
               std::invalid_argument);
  auto wide = servos(ft::Series::kScs, 1);
  wide[0].limits.position_max = 170 * kDeg;  // beyond the 1023 steps of an SCS
  try {
    FeetechBus("ft", "/dev/null", 1'000'000, wide, {0.0}, fast(ft::Series::kScs));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("outside the 0..1023 of this series"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace facectl
