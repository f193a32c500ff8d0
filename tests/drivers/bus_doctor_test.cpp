// `bus doctor` against real peers: the libmodbus server with simulated boards,
// simulated CAN devices on the in-process wire, and simulated DYNAMIXEL and
// Feetech servos and a Maestro on a pty.
#include "drivers/bus_doctor.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "drivers/protocol/feetech_packet.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/custom_can_board_sim.hpp"
#include "sim/devices/dynamixel_pty_wire.hpp"
#include "sim/devices/feetech_pty_wire.hpp"
#include "sim/devices/maestro_pty_wire.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "sim/devices/modbus_board_server.hpp"
#include "tests/drivers/can_test_axes.hpp"
#include "tests/drivers/stalling_modbus_server.hpp"

namespace facectl {
namespace {

bool has(const DoctorReport& r, DoctorFinding::Level level, const std::string& text) {
  for (const auto& f : r.findings) {
    if (f.level == level && f.text.find(text) != std::string::npos) return true;
  }
  return false;
}
using L = DoctorFinding::Level;

TEST(BusDoctor, ModbusReportsRoundTripsAndNamesABoardThatDoesNotAnswer) {
  sim::ModbusActuatorBoard board1(1, std::vector<sim::BoardChannel>(8));
  auto server = sim::ModbusBoardServer::tcp({&board1});  // board 2 is missing
  ModbusEndpoint ep;
  ep.port = server->port();
  const DoctorReport r =
      diagnose_modbus("modbus0", ep, testing::rotary_axes(14), ModbusTiming{}, 10);
  std::printf("%s", r.to_text().c_str());
  EXPECT_TRUE(has(r, L::kOk, "board 1: round trip min"));
  EXPECT_TRUE(has(r, L::kProblem, "board 2: does not answer"));
  EXPECT_TRUE(r.has_problems());
  EXPECT_TRUE(has(r, L::kOk, "response timeout 20 ms"));
  EXPECT_EQ(board1.target_writes() + board1.target_writes_while_disabled(), 0u) << "doctor wrote";
}

TEST(BusDoctor, ModbusFlagsKnownBadDefaultsAndBoardState) {
  sim::ModbusActuatorBoard board1(1, std::vector<sim::BoardChannel>(4));
  board1.inject_fault(modbus_map::FaultCode::kOverTemperature);
  auto server = sim::ModbusBoardServer::tcp({&board1});
  ModbusEndpoint ep;
  ep.port = server->port();
  ModbusTiming slow;
  slow.response_timeout_s = 0.5;
  const DoctorReport r = diagnose_modbus("modbus0", ep, testing::rotary_axes(6), slow, 5);
  SCOPED_TRACE(r.to_text());
  EXPECT_TRUE(has(r, L::kWarning, "libmodbus's 500 ms default"));
  EXPECT_TRUE(has(r, L::kWarning, "board 1: reports fault code 2"));
  EXPECT_TRUE(has(r, L::kProblem, "board 1: has 4 channels, the rig uses 6"));
}

// A reply that starts and stalls is given up after the bus's byte timeout,
// not libmodbus's 500 ms default (issue 21, item 8).
TEST(BusDoctor, ModbusGivesUpOnAStalledReplyAfterTheByteTimeout) {
  testing::StallingModbusServer server;
  ModbusEndpoint ep;
  ep.port = server.port();
  ModbusTiming timing;
  timing.response_timeout_s = 0.4;
  timing.byte_timeout_s = 0.05;
  const auto t0 = std::chrono::steady_clock::now();
  const DoctorReport r = diagnose_modbus("modbus0", ep, testing::rotary_axes(2), timing, 1);
  const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0);
  SCOPED_TRACE(r.to_text());
  EXPECT_EQ(server.requests(), 1);
  EXPECT_TRUE(has(r, L::kProblem, "board 1: does not answer"));
  EXPECT_TRUE(has(r, L::kOk, "byte timeout 50 ms"));
  EXPECT_LT(ms.count(), 300.0) << "the stalled reply was waited for past the 50 ms byte timeout";
}

TEST(BusDoctor, TheUsbSerialLatencyTimerIsReadFromSysfs) {
  const auto root =
      std::filesystem::temp_directory_path() / ("facectl_sysfs_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(root / "class/tty/ttyUSB0/device");
  std::ofstream(root / "class/tty/ttyUSB0/device/latency_timer") << "16\n";
  EXPECT_EQ(usb_serial_latency_timer_ms("/dev/ttyUSB0", root.string()), 16);
  EXPECT_FALSE(usb_serial_latency_timer_ms("/dev/ttyS0", root.string()));
  std::filesystem::remove_all(root);
}

TEST(BusDoctor, Cia402DrivesAreReadByTypeAndAMissingOneIsNamed) {
  MemoryCanLink link;
  sim::Cia402DriveSim d1(1, testing::fast_plant(), 1000.0, 0.0);
  sim::Cia402DriveSim d2(2, testing::fast_plant(), 1000.0, 0.0);
  sim::CanDeviceNetwork net(link.devices(), {&d1, &d2});
  net.start(200);
  const DoctorReport r = diagnose_can("can0", link.host(), "cia402", testing::rotary_axes(3),
                                      CanBusOptions{}, 200.0, 1'000'000, 0.3);
  std::printf("%s", r.to_text().c_str());
  EXPECT_TRUE(has(r, L::kOk, "drive 1: SDO round trip"));
  EXPECT_TRUE(has(r, L::kOk, "device type 0x00020192 (CiA 402)"));
  EXPECT_TRUE(has(r, L::kProblem, "drive 3: no answer"));
  EXPECT_TRUE(has(r, L::kOk, "load: can0: 9 frames per cycle at 200 Hz"));
  EXPECT_EQ(d1.state(), cia402::DriveState::kSwitchOnDisabled) << "the doctor changed a drive";
  EXPECT_EQ(d1.sdo_writes(), 0u);
}

TEST(BusDoctor, CustomBoardsAreHeardAndErrorFramesAndOverloadAreProblems) {
  MemoryCanLink link;
  std::vector<std::unique_ptr<sim::CustomCanBoardSim>> boards;
  std::vector<sim::CanDevice*> devices;
  for (int n = 1; n <= 3; ++n) {  // board 4 is missing
    boards.push_back(std::make_unique<sim::CustomCanBoardSim>(n, std::vector<sim::BoardChannel>(3),
                                                              custom_can::Width::kInt16));
    devices.push_back(boards.back().get());
  }
  sim::CanDeviceNetwork net(link.devices(), devices);
  net.start(200);
  link.host().inject_error(CanError::kBusOff);
  const DoctorReport r = diagnose_can("can0", link.host(), "custom", testing::rotary_axes(12),
                                      CanBusOptions{}, 1000.0, 1'000'000, 0.2);
  SCOPED_TRACE(r.to_text());
  EXPECT_TRUE(has(r, L::kOk, "board 3: heartbeat"));
  EXPECT_TRUE(has(r, L::kProblem, "board 4: not heard"));
  EXPECT_TRUE(has(r, L::kProblem, "error frames: bus-off x1"));
  EXPECT_TRUE(has(r, L::kProblem, "108.0% of 1000000 bit/s (refused"));
}

TEST(BusDoctor, DynamixelNamesEachServosStateAndOnesNotInTheRig) {
  std::vector<std::unique_ptr<sim::DynamixelServoSim>> servos;
  servos.push_back(std::make_unique<sim::DynamixelServoSim>(1, 1060, 2048));
  servos.push_back(std::make_unique<sim::DynamixelServoSim>(2, 1020, 2048));
  servos.push_back(std::make_unique<sim::DynamixelServoSim>(7, 1060, 2048));  // not in the rig
  servos[1]->raise_hardware_error(0x04);                                      // overheating
  sim::DynamixelPtyWire wire(std::move(servos));
  std::vector<ActuatorModel> acts = testing::rotary_axes(3);  // IDs 1, 2, 3; +-30 deg
  for (auto& a : acts) a.encoding = {ActuatorEncoding::Raw::kInt32, 4096.0 / 360.0, 2048.0};
  const std::uint64_t writes_before = wire.requests_of(0x03) + wire.requests_of(0x83);
  const DoctorReport r = diagnose_dynamixel("dxl", wire.device(), 1'000'000, acts, {}, 5);
  std::printf("%s", r.to_text().c_str());
  EXPECT_TRUE(has(r, L::kOk, "servo 1 (axis1): XL430-W250, firmware 46, 5/5 PINGs answered"));
  EXPECT_TRUE(has(r, L::kOk, "servo 1 (axis1): Return Delay Time 500 us; facectl writes 0 us"));
  EXPECT_TRUE(has(r, L::kOk, "servo 1 (axis1): 12.0 V, 28 deg C"));
  EXPECT_TRUE(has(r, L::kOk, "servo 2 (axis2): XM430-W350"));
  EXPECT_TRUE(has(r, L::kProblem, "servo 2 (axis2): Hardware Error Status: overheating"));
  EXPECT_TRUE(has(r, L::kProblem, "servo 3 (axis3): no answer to 5 PINGs"));
  EXPECT_TRUE(has(r, L::kWarning, "servo ID 7 answers but is not in the rig"));
  EXPECT_TRUE(has(r, L::kOk, "3 servo(s) answered a broadcast PING"));
  EXPECT_TRUE(r.has_problems());
  // Read-only: no WRITE, no SYNC WRITE reached the servos.
  EXPECT_EQ(wire.requests_of(0x03) + wire.requests_of(0x83), writes_before);
}

// Servos 1 and 2 of a three-servo rig, and ID 9 that the rig lacks. Servo 1
// is outside the hard range with torque on; servo 2 is overheating and at
// Response Level 0.
void check_feetech_doctor(ft::Series series, const std::string& model) {
  const int steps = ft::steps_per_turn(series);
  std::vector<std::unique_ptr<sim::FeetechServoSim>> servos;
  servos.push_back(std::make_unique<sim::FeetechServoSim>(1, series, steps * 3 / 4));  // +90 deg
  servos.push_back(std::make_unique<sim::FeetechServoSim>(2, series));
  servos.push_back(std::make_unique<sim::FeetechServoSim>(9, series));  // not in the rig
  std::vector<std::uint8_t> reply;
  const std::uint8_t torque_on[] = {ft::kTorqueEnable, 1};
  servos[0]->handle(1, scs::kWrite, torque_on, 0, reply);  // as another program would
  const std::uint8_t level_0[] = {ft::kResponseLevel, 0};
  servos[1]->handle(2, scs::kWrite, level_0, 0, reply);
  servos[1]->raise_error(ft::kErrOverheat);
  sim::FeetechPtyWire wire(std::move(servos));
  std::vector<ActuatorModel> acts = testing::rotary_axes(3);  // IDs 1, 2, 3; +-30 deg
  for (auto& a : acts) a.encoding = {ActuatorEncoding::Raw::kUint16, steps / 360.0, steps / 2.0};
  FeetechOptions options;
  options.series = series;
  options.return_delay_us = 10;
  // The simulated servos answer from a thread that a loaded machine can hold back past the
  // default 10 ms, which the report would count as a lost PING.
  options.response_timeout_s = 0.05;
  const DoctorReport r = diagnose_feetech("ft", wire.device(), 1'000'000, acts, options, 5);
  std::printf("%s", r.to_text().c_str());
  EXPECT_TRUE(has(r, L::kOk, "servo 1 (axis1): model number " + model + ", 5/5 PINGs answered"));
  EXPECT_TRUE(has(r, L::kWarning, "servo 1 (axis1): torque is on"));
  EXPECT_TRUE(has(r, L::kOk, "servo 1 (axis1): Return Delay 0 us; facectl writes 10 us"));
  EXPECT_TRUE(has(r, L::kOk, "servo 1 (axis1): 7.4 V, 27 deg C"));
  EXPECT_TRUE(has(r, L::kWarning, "servo 1 (axis1): at 90.0 deg, outside the rig's hard range"));
  EXPECT_FALSE(has(r, L::kProblem, "servo 1 (axis1)"));
  EXPECT_TRUE(has(r, L::kProblem, "servo 2 (axis2): error status: overheating"));
  EXPECT_TRUE(has(r, L::kOk, "servo 2 (axis2): Response Level 0"));
  EXPECT_FALSE(has(r, L::kWarning, "servo 2 (axis2): at"));
  EXPECT_TRUE(has(r, L::kProblem, "servo 3 (axis3): no answer to 5 PINGs"));
  EXPECT_TRUE(has(r, L::kWarning, "servo ID 9 answers but is not in the rig"));
  EXPECT_TRUE(has(r, L::kOk, "IDs 0..20 not in the rig: 1 answered a PING"));
  EXPECT_TRUE(r.has_problems());
  // Read-only: no WRITE, REG_WRITE, ACTION or SYNC WRITE reached the servos.
  for (const std::uint8_t i : {scs::kWrite, scs::kRegWrite, scs::kAction, scs::kSyncWrite}) {
    EXPECT_EQ(wire.requests_of(i), 0u) << "instruction " << int{i};
  }
  wire.with_servo(1, [](sim::FeetechServoSim& s) {
    EXPECT_TRUE(s.torque());
    EXPECT_EQ(s.eeprom_writes(), 0u);
  });
}

TEST(BusDoctor, FeetechStsNamesEachServosStateAndOnesNotInTheRig) {
  check_feetech_doctor(ft::Series::kSts, "777");
}

TEST(BusDoctor, FeetechScsNamesEachServosStateAndOnesNotInTheRig) {
  check_feetech_doctor(ft::Series::kScs, "1284");
}

TEST(BusDoctor, FeetechMutedServoIsAProblemAndAMissingPortIsNamed) {
  std::vector<std::unique_ptr<sim::FeetechServoSim>> servos;
  servos.push_back(std::make_unique<sim::FeetechServoSim>(1, ft::Series::kSts));
  servos.push_back(std::make_unique<sim::FeetechServoSim>(2, ft::Series::kSts));
  sim::FeetechPtyWire wire(std::move(servos));
  wire.faults().mute_id = 2;
  std::vector<ActuatorModel> acts = testing::rotary_axes(2);
  for (auto& a : acts) a.encoding = {ActuatorEncoding::Raw::kUint16, 4096 / 360.0, 2048.0};
  const DoctorReport r = diagnose_feetech("ft", wire.device(), 1'000'000, acts, {}, 3);
  SCOPED_TRACE(r.to_text());
  EXPECT_TRUE(has(r, L::kOk, "servo 1 (axis1): model number 777, 3/3 PINGs answered"));
  EXPECT_FALSE(has(r, L::kOk, "servo 1 (axis1): Return Delay"));  // 0 as the bus writes
  EXPECT_TRUE(has(r, L::kProblem, "servo 2 (axis2): no answer to 3 PINGs"));
  EXPECT_TRUE(has(r, L::kOk, "IDs 0..20 not in the rig: 0 answered a PING"));
  const DoctorReport gone =
      diagnose_feetech("ft", "/dev/facectl-no-such-port", 1'000'000, acts, {});
  EXPECT_TRUE(has(gone, L::kProblem, "cannot open: "));
}

TEST(BusDoctor, MaestroReportsItsErrorRegisterAndEachChannelsPulse) {
  sim::MaestroSim maestro(12);
  std::vector<std::uint8_t> reply;
  for (const int b : {0x84, 0x02, 0x70, 0x2E})
    maestro.feed(static_cast<std::uint8_t>(b), 0, reply);  // 1500 us
  maestro.raise_error(0x0020);  // serial timeout: it sent everything home (Off)
  for (const int b : {0x84, 0x01, 0x70, 0x3E})
    maestro.feed(static_cast<std::uint8_t>(b), 0, reply);  // 2000 us
  sim::MaestroPtyWire wire(std::move(maestro));
  std::vector<ActuatorModel> acts = testing::rotary_axes(3);  // channels 1, 2, 3; +-30 deg
  for (auto& a : acts) a.encoding = {ActuatorEncoding::Raw::kUint16, 10.0, 1500.0};
  const DoctorReport r = diagnose_maestro("maestro", wire.device(), 115200, acts, {}, 5);
  std::printf("%s", r.to_text().c_str());
  EXPECT_TRUE(has(r, L::kOk, "5/5 Get Errors answered, round trip median"));
  EXPECT_TRUE(has(r, L::kProblem, "error register 0x0020: serial timeout (cleared by reading it"));
  EXPECT_TRUE(
      has(r, L::kWarning, "channel 1 (axis1): sending 2000.00 us (outside the rig's hard range"));
  EXPECT_TRUE(has(r, L::kOk, "channel 2 (axis2): no pulses (off)"));
  EXPECT_TRUE(has(r, L::kOk, "channel 3 (axis3): no pulses (off)"));
  EXPECT_TRUE(has(r, L::kOk, "Serial Settings: Timeout"));
  EXPECT_TRUE(r.has_problems());
  // Read-only: no target reached the Maestro.
  std::uint64_t targets = 0, errors = 0;
  wire.with_maestro([&](sim::MaestroSim& m) {
    targets = m.commands(0x84) + m.commands(0x9F);
    errors = m.errors();
  });
  EXPECT_EQ(targets, 2u) << "the two this test sent";
  EXPECT_EQ(errors, 0u);
  // Nothing there: one problem, no throw.
  const DoctorReport gone =
      diagnose_maestro("maestro", "/dev/facectl-no-such-port", 115200, acts, {});
  EXPECT_TRUE(has(gone, L::kProblem, "cannot open: "));
}

}  // namespace
}  // namespace facectl
