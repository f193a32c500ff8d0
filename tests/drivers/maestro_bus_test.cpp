// The real MaestroBus (a serial port, its own I/O thread) against the
// simulated Maestro of sim/devices/maestro_sim.hpp on a pseudo-terminal, in
// both protocols, and the fault matrix: no reply, short replies, error bits,
// a port lost and reopened, Set Multiple Targets on a Micro Maestro.
#include "drivers/maestro/maestro_bus.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "drivers/protocol/maestro_serial.hpp"
#include "sim/devices/maestro_pty_wire.hpp"

namespace facectl {
namespace {

using namespace std::chrono_literals;
using sim::MaestroPtyWire;
using sim::MaestroSim;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Hobby servos on channels first..first+count-1: 1500 us at 0 deg, 10 us per
// degree, hard limits +-40 deg (1100..1900 us, inside the factory range).
std::vector<ActuatorModel> servos(int count, int first = 0) {
  std::vector<ActuatorModel> a(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    ActuatorModel& m = a[static_cast<std::size_t>(i)];
    m.name = "servo" + std::to_string(i);
    m.address = first + i;
    m.encoding = {ActuatorEncoding::Raw::kUint16, 10.0, 1500.0};
    m.limits.position_min = -40 * kDeg;
    m.limits.position_max = 40 * kDeg;
    m.limits.soft_min = -35 * kDeg;
    m.limits.soft_max = 35 * kDeg;
  }
  return a;
}

MaestroOptions fast(maestro::Protocol p = maestro::Protocol::kCompact) {
  MaestroOptions o;
  o.protocol = p;
  o.cycle_period_s = 0.005;
  o.response_timeout_s = 0.020;
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

int target(MaestroPtyWire& w, int channel) {
  int v = 0;
  w.with_maestro([&](MaestroSim& m) { v = m.target(channel); });
  return v;
}

std::string reason(const MaestroBus& bus) {
  return bus.status().reason;
}

// The tick, as the controller runs it, for `n` ticks of 1 ms.
void ticks(MaestroBus& bus, std::vector<double>& cmd, int n) {
  std::vector<double> meas(cmd.size());
  for (int k = 0; k < n; ++k) {
    bus.read({0, 0.001}, meas);
    bus.write({0, 0.001}, cmd);
    std::this_thread::sleep_for(1ms);
  }
}

// One channel enabled and following 10 deg (1600 us).
bool running_at_1600(MaestroBus& bus, MaestroPtyWire& wire, std::vector<double>& cmd) {
  if (!eventually([&] { return bus.ready(); })) return false;
  bus.set_enabled(true);
  ticks(bus, cmd, 5);
  return eventually([&] { return target(wire, 0) == 4 * 1600; });
}

// After a fault the channel stays off while the controller goes on writing,
// and follows again once disabled and enabled.
bool off_until_disabled(MaestroBus& bus, MaestroPtyWire& wire, std::vector<double>& cmd) {
  ticks(bus, cmd, 20);
  if (target(wire, 0) != 0) return false;
  bus.set_enabled(false);
  bus.set_enabled(true);
  ticks(bus, cmd, 5);
  return eventually([&] { return target(wire, 0) == 4 * 1600; });
}

class MaestroBusProtocols : public ::testing::TestWithParam<maestro::Protocol> {};

TEST_P(MaestroBusProtocols, SendsNoPulsesUntilEnabledThenFollowsTheCommands) {
  MaestroPtyWire wire(MaestroSim(12, 12));
  MaestroBus bus("maestro", wire.device(), 115200, servos(3, 2), {0.0, 0.0, 0.0}, fast(GetParam()));
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  EXPECT_FALSE(bus.status().fault) << reason(bus);
  for (int c = 2; c < 5; ++c) EXPECT_EQ(target(wire, c), 0) << "no pulses while disabled";
  bus.set_enabled(true);
  std::vector<double> cmd = {10 * kDeg, -20 * kDeg, 0.0};
  ticks(bus, cmd, 5);
  ASSERT_TRUE(eventually([&] { return target(wire, 2) == 4 * 1600; })) << target(wire, 2);
  EXPECT_EQ(target(wire, 3), 4 * 1300);
  EXPECT_EQ(target(wire, 4), 4 * 1500);
  // read() reports what the Maestro says it sends.
  std::vector<double> meas(3);
  ASSERT_TRUE(eventually([&] {
    bus.read({0, 0.001}, meas);
    return std::abs(meas[0] - 10 * kDeg) < 0.01 && std::abs(meas[1] + 20 * kDeg) < 0.01;
  })) << meas[0] / kDeg
      << " " << meas[1] / kDeg;
  // Beyond the hard limits: clamped to them.
  cmd[0] = 60 * kDeg;
  ticks(bus, cmd, 5);
  EXPECT_TRUE(eventually([&] { return target(wire, 2) == 4 * 1900; })) << target(wire, 2);
  bus.set_enabled(false);
  EXPECT_TRUE(eventually([&] { return target(wire, 2) == 0 && target(wire, 3) == 0; }));
  std::uint64_t other = 0;
  wire.with_maestro([&](MaestroSim& m) { other = m.errors(); });
  EXPECT_EQ(other, 0u) << "every byte parsed without a protocol error";
  EXPECT_EQ(bus.stats().timeouts + bus.stats().short_replies, 0u);
}

INSTANTIATE_TEST_SUITE_P(CompactAndPololu, MaestroBusProtocols,
                         ::testing::Values(maestro::Protocol::kCompact,
                                           maestro::Protocol::kPololu));

TEST(MaestroBus, APololuPacketForAnotherDeviceNumberIsNotAnswered) {
  MaestroPtyWire wire(MaestroSim(12, 12));
  MaestroOptions o = fast(maestro::Protocol::kPololu);
  o.device_number = 13;
  MaestroBus bus("maestro", wire.device(), 115200, servos(1), {0.0}, o);
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus), "maestro: the Maestro at " + wire.device() +
                             " is not answering within 150 ms (serial mode, baud rate, protocol, "
                             "device number?)");
}

TEST(MaestroBus, EnablesBumplesslyAndPerActuator) {
  MaestroPtyWire wire(MaestroSim(12));
  MaestroBus bus("maestro", wire.device(), 115200, servos(2), {2 * kDeg, 0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  EXPECT_EQ(target(wire, 0), 0);
  std::vector<std::uint8_t> on = {1, 0};
  bus.set_actuators_enabled(on);
  // No write since the enable: the channel starts where it was last reported.
  EXPECT_TRUE(eventually([&] { return target(wire, 0) == 4 * 1520; })) << target(wire, 0);
  std::this_thread::sleep_for(30ms);
  EXPECT_EQ(target(wire, 0), 4 * 1520);
  EXPECT_EQ(target(wire, 1), 0) << "channel 1 not enabled";
  EXPECT_TRUE(bus.output_on(0));
  EXPECT_FALSE(bus.output_on(1));
  std::vector<double> cmd = {20 * kDeg, 20 * kDeg};
  ticks(bus, cmd, 5);
  EXPECT_TRUE(eventually([&] { return target(wire, 0) == 4 * 1700; }));
  EXPECT_EQ(target(wire, 1), 0);
}

TEST(MaestroBus, HoldsThePulseItWasSendingUntilTheFirstCommand) {
  MaestroPtyWire wire(MaestroSim(12));
  MaestroBus bus("maestro", wire.device(), 115200, servos(1), {5 * kDeg}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  bus.set_enabled(true);
  // Off until now: the hold is the last position reported (the initial one).
  EXPECT_TRUE(eventually([&] { return target(wire, 0) == 4 * 1550; })) << target(wire, 0);
}

TEST(MaestroBus, ErrorBitsAreAFaultThatSwitchesEveryOutputOffUntilDisabled) {
  MaestroPtyWire wire(MaestroSim(12));
  MaestroBus bus("maestro", wire.device(), 115200, servos(2), {0.0, 0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  bus.set_enabled(true);
  std::vector<double> cmd = {10 * kDeg, 10 * kDeg};
  ticks(bus, cmd, 5);
  ASSERT_TRUE(eventually([&] { return target(wire, 0) == 4 * 1600; }));
  wire.with_maestro([](MaestroSim& m) {
    m.raise_error(maestro::kErrSerialTimeout | maestro::kErrSerialOverrun);
  });
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus),
            "maestro: Maestro error: serial timeout (outputs off; see docs/PROTOCOLS.md, Maestro)");
  std::vector<ActuatorHealth> health(2);
  bus.read_health(health);
  EXPECT_EQ(health[0].hardware_error, 0x22u);
  EXPECT_EQ(health[1].hardware_error, 0x22u);
  // Still enabled, still writing: the outputs stay off.
  ticks(bus, cmd, 30);
  EXPECT_EQ(target(wire, 0), 0);
  EXPECT_EQ(target(wire, 1), 0);
  EXPECT_FALSE(bus.output_on(0));
  // Disabled and enabled again: the register reads 0 now, the fault clears.
  bus.set_enabled(false);
  ASSERT_TRUE(eventually([&] { return !bus.status().fault; })) << reason(bus);
  bus.set_enabled(true);
  ticks(bus, cmd, 5);
  EXPECT_TRUE(eventually([&] { return target(wire, 0) == 4 * 1600; })) << target(wire, 0);
  EXPECT_GE(bus.stats().error_reports, 1u);
}

TEST(MaestroBus, ASilentMaestroIsAFaultAndItsReturnClearsIt) {
  MaestroPtyWire wire(MaestroSim(12));
  MaestroBus bus("maestro", wire.device(), 115200, servos(1), {0.0}, fast());
  std::vector<double> cmd = {10 * kDeg};
  ASSERT_TRUE(running_at_1600(bus, wire, cmd)) << reason(bus);
  wire.faults().mute = true;
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_NE(reason(bus).find("is not answering within 150 ms"), std::string::npos) << reason(bus);
  EXPECT_GT(bus.stats().timeouts, 0u);
  EXPECT_TRUE(eventually([&] { return target(wire, 0) == 0; })) << "pulses off on silence";
  wire.faults().mute = false;
  EXPECT_TRUE(eventually([&] { return !bus.status().fault; })) << reason(bus);
  // Latched off until the controller disables it.
  EXPECT_TRUE(off_until_disabled(bus, wire, cmd));
}

TEST(MaestroBus, ShortRepliesAreCountedAndNotTakenAsPositions) {
  MaestroPtyWire wire(MaestroSim(12));
  MaestroBus bus("maestro", wire.device(), 115200, servos(2), {3 * kDeg, 4 * kDeg}, fast());
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  wire.faults().truncate_next = 5;
  ASSERT_TRUE(eventually([&] { return bus.stats().short_replies >= 5; }))
      << bus.stats().short_replies;
  EXPECT_FALSE(bus.status().fault) << "a few short replies are not a silence";
  std::vector<double> meas(2);
  bus.read({0, 0.001}, meas);
  EXPECT_DOUBLE_EQ(meas[0], 3 * kDeg) << "no pulses: the last known position stands";
  EXPECT_DOUBLE_EQ(meas[1], 4 * kDeg);
}

TEST(MaestroBus, ALostPortIsAFaultAndIsReopened) {
  MaestroPtyWire wire(MaestroSim(12));
  MaestroBus bus("maestro", wire.device(), 115200, servos(1), {0.0}, fast());
  std::vector<double> cmd = {10 * kDeg};
  ASSERT_TRUE(running_at_1600(bus, wire, cmd)) << reason(bus);
  wire.unplug();
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus), "maestro: serial port " + wire.device() + " lost or cannot be opened");
  EXPECT_FALSE(bus.output_on(0));
  wire.replug();  // and the Maestro, USB-powered, starts afresh
  ASSERT_TRUE(eventually([&] { return !bus.status().fault && bus.ready(); })) << reason(bus);
  EXPECT_GE(bus.stats().reopens, 1u);
  // Off until the controller disables it, then on again.
  EXPECT_TRUE(off_until_disabled(bus, wire, cmd));
}

TEST(MaestroBus, SetsEveryChannelWithOneMultipleTargetsCommand) {
  MaestroPtyWire wire(MaestroSim(12));
  MaestroOptions o = fast();
  o.multiple_targets = true;
  MaestroBus bus("maestro", wire.device(), 115200, servos(3, 4), {0.0, 0.0, 0.0}, o);
  ASSERT_TRUE(eventually([&] { return bus.ready(); })) << reason(bus);
  bus.set_enabled(true);
  std::vector<double> cmd = {1 * kDeg, 2 * kDeg, 3 * kDeg};
  ticks(bus, cmd, 5);
  ASSERT_TRUE(eventually([&] { return target(wire, 6) == 4 * 1530; })) << target(wire, 6);
  EXPECT_EQ(target(wire, 4), 4 * 1510);
  std::uint64_t multiple = 0, single = 0;
  const auto count = [&] {
    wire.with_maestro([&](MaestroSim& m) {
      multiple = m.commands(maestro::kSetMultipleTargets);
      single = m.commands(maestro::kSetTarget);
    });
  };
  EXPECT_TRUE(eventually([&] {
    count();
    return multiple > 10;
  }));
  EXPECT_EQ(single, 0u);
}

TEST(MaestroBus, MultipleTargetsOnAMicroMaestroIsAFaultSayingSo) {
  MaestroPtyWire wire(MaestroSim(6));
  MaestroOptions o = fast();
  o.multiple_targets = true;
  MaestroBus bus("maestro", wire.device(), 115200, servos(2), {0.0, 0.0}, o);
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus),
            "maestro: Maestro error: serial protocol error with multiple_targets: true (a Micro "
            "Maestro 6 has no Set Multiple Targets; set it false)");
}

TEST(MaestroBus, APortThatIsNotThereIsAFault) {
  MaestroBus bus("maestro", "/dev/facectl-no-such-port", 115200, servos(1), {0.0}, fast());
  ASSERT_TRUE(eventually([&] { return bus.status().fault; }));
  EXPECT_EQ(reason(bus), "maestro: serial port /dev/facectl-no-such-port lost or cannot be opened");
}

TEST(MaestroBus, RefusesBadChannelsLimitsAndBlocks) {
  const auto refusal = [](std::vector<ActuatorModel> a, MaestroOptions o = {}) {
    try {
      MaestroBus bus("m", "/dev/null", 115200, a, std::vector<double>(a.size(), 0.0), o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  auto a = servos(2);
  a[1].address = 24;
  EXPECT_EQ(refusal(a), "bus m: actuator servo1: channel 24, expected 0..23");
  a[1].address = 0;
  EXPECT_EQ(refusal(a), "bus m: actuators servo0 and servo1 share channel 0");
  a = servos(1);
  a[0].encoding.offset = 500;  // -60 deg: -100 us, saturated to 0 by uint16: "no pulses"
  a[0].limits.position_min = -60 * kDeg;
  EXPECT_EQ(refusal(a),
            "bus m: actuator servo0: its hard limits are pulses 0..900 us, outside the "
            "Maestro's 1..4095 us (check encoding)");
  a = servos(2);
  a[1].address = 3;
  MaestroOptions o;
  o.multiple_targets = true;
  EXPECT_EQ(refusal(a, o),
            "bus m: multiple_targets sets one block of channels: channels 0..3 must all be "
            "actuators of the bus");
}

}  // namespace
}  // namespace facectl
