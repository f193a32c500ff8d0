// The drivers' seam calls allocate nothing: this binary counts every malloc,
// calloc and realloc made on the calling thread while the tick's calls run
// (read, write, set_enabled, status), through enabling, running, faults and
// disabling. The devices and the Modbus and DYNAMIXEL I/O threads are not
// counted: they are not the tick.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "drivers/can/cia402_bus.hpp"
#include "drivers/can/custom_can_bus.hpp"
#include "drivers/dynamixel/dynamixel_bus.hpp"
#include "drivers/feetech/feetech_bus.hpp"
#include "drivers/i2c/pca9685_bus.hpp"
#include "drivers/maestro/maestro_bus.hpp"
#include "drivers/modbus/modbus_bus.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/custom_can_board_sim.hpp"
#include "sim/devices/dynamixel_pty_wire.hpp"
#include "sim/devices/feetech_pty_wire.hpp"
#include "sim/devices/maestro_pty_wire.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "sim/devices/memory_i2c_bus.hpp"
#include "sim/devices/modbus_board_server.hpp"
#include "tests/drivers/can_test_axes.hpp"
#include "tests/support/allocation_counter.hpp"

namespace facectl {
namespace {

using testing::fast_plant;
using testing::kDeg;

// Runs `tick` with allocation counting on for this thread only.
template <typename F>
long allocations_in(F&& tick) {
  testing::begin_counting_allocations();
  tick();
  return testing::end_counting_allocations();
}

TEST(DriverNoAllocation, TheCountingHookSeesAnAllocation) {
  EXPECT_GT(allocations_in([] { delete new std::vector<int>(100); }), 0);
}

TEST(DriverNoAllocation, CanBusesAllocateNothingInTheTick) {
  MemoryCanLink link(1024);
  std::vector<std::unique_ptr<sim::Cia402DriveSim>> drives;
  std::vector<sim::CanDevice*> devices;
  for (int n = 1; n <= 3; ++n) {
    drives.push_back(std::make_unique<sim::Cia402DriveSim>(n, fast_plant(), 20000.0, 0.0));
    devices.push_back(drives.back().get());
  }
  sim::CanDeviceNetwork net(link.devices(), devices);
  Cia402Bus bus("can0", link.host(), testing::rotary_axes(3), std::vector<double>(3, 0.0));
  std::vector<double> cmd(3, 5 * kDeg), meas(3);
  std::int64_t now = 1'000'000'000;
  long total = 0;
  bool ran = false;
  for (int k = 0; k < 400; ++k) {
    now += 1'000'000;
    if (k == 299) ran = drives[0]->state() == cia402::DriveState::kOperationEnabled;
    if (k == 300) drives[1]->inject_fault(0x2310);  // a fault, then the disable of FAULT
    total += allocations_in([&] {
      if (k == 1) bus.set_enabled(true);
      bus.read({now, 0.001}, meas);
      if (bus.status().fault && k > 300) bus.set_enabled(false);
      bus.write({now, 0.001}, cmd);
    });
    net.poll(now);
  }
  EXPECT_TRUE(ran) << "the drives never reached operation enabled";
  EXPECT_EQ(total, 0);
}

// The formatted reasons (an SDO abort, a wrong mode) and the segmented upload
// run in the tick too: a fixed buffer, no allocation.
TEST(DriverNoAllocation, Cia402SdoFailuresAndSegmentedUploadsAllocateNothing) {
  MemoryCanLink link(1024);
  sim::Cia402DriveSim d1(1, fast_plant(), 20000.0, 0.0), d2(2, fast_plant(), 20000.0, 0.0);
  d1.set_upload_form(sim::Cia402DriveSim::UploadForm::kSegmented);
  d1.force_mode_display(3);
  d2.refuse_object(0x607F);
  sim::CanDeviceNetwork net(link.devices(), {&d1, &d2});
  Cia402Bus bus("can0", link.host(), testing::rotary_axes(2), std::vector<double>(2, 0.0));
  std::vector<double> cmd(2, 0.0), meas(2);
  std::int64_t now = 1'000'000'000;
  long total = 0;
  for (int k = 0; k < 200; ++k) {
    now += 1'000'000;
    total += allocations_in([&] {
      if (k == 1) bus.set_enabled(true);
      bus.read({now, 0.001}, meas);
      bus.write({now, 0.001}, cmd);
      (void)bus.status();
    });
    net.poll(now);
  }
  EXPECT_EQ(bus.last_sdo_abort(1), 0x06020000u) << "the abort path ran";
  EXPECT_EQ(d1.sdo_uploads(), 1u) << "the segmented upload ran";
  EXPECT_EQ(total, 0);
}

TEST(DriverNoAllocation, CustomCanBusAllocatesNothingInTheTick) {
  MemoryCanLink link(1024);
  std::vector<sim::BoardChannel> ch(3);
  for (auto& c : ch) c.plant = fast_plant();
  // A non-default encoding on one channel: its arithmetic runs in the tick too.
  const ActuatorEncoding offset{ActuatorEncoding::Raw::kUint16, 50.0, 32768.0};
  ch[1].encoding = offset;
  std::vector<ActuatorModel> acts = testing::rotary_axes(3);
  acts[1].encoding = offset;
  sim::CustomCanBoardSim board(1, ch, custom_can::Width::kInt16);
  sim::CanDeviceNetwork net(link.devices(), {&board});
  CustomCanBus bus("can0", link.host(), acts, std::vector<double>(3, 0.0));
  std::vector<double> cmd(3, 5 * kDeg), meas(3);
  std::int64_t now = 1'000'000'000;
  long total = 0;
  for (int k = 0; k < 200; ++k) {
    now += 1'000'000;
    if (k == 100) link.host().inject_error(CanError::kBusOff);
    total += allocations_in([&] {
      if (k == 1) bus.set_enabled(true);
      if (k == 150) bus.set_enabled(false);
      bus.read({now, 0.001}, meas);
      bus.write({now, 0.001}, cmd);
      (void)bus.status();
    });
    net.poll(now);
  }
  EXPECT_GT(board.commands(), 100u);
  EXPECT_EQ(total, 0);
}

TEST(DriverNoAllocation, ModbusBusAllocatesNothingInTheTick) {
  std::vector<sim::BoardChannel> ch(4);
  const ActuatorEncoding offset{ActuatorEncoding::Raw::kUint16, 50.0, 32768.0};
  ch[2].encoding = offset;
  sim::ModbusActuatorBoard board(1, ch);
  auto server = sim::ModbusBoardServer::tcp({&board});
  std::vector<ActuatorModel> acts = testing::rotary_axes(4);
  acts[2].encoding = offset;
  ModbusEndpoint ep;
  ep.port = server->port();
  ModbusBus bus("modbus0", ep, acts, std::vector<double>(4, 0.0));
  std::vector<double> cmd(4, 2 * kDeg), meas(4);
  long total = 0;
  for (int k = 0; k < 300; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (k == 200) server->faults().silent = true;
    total += allocations_in([&] {
      if (k == 1) bus.set_enabled(true);
      bus.read({0, 0.001}, meas);
      bus.write({0, 0.001}, cmd);
      (void)bus.status();
      if (k == 299) bus.set_enabled(false);
    });
  }
  EXPECT_GT(board.target_writes(), 50u);
  EXPECT_EQ(total, 0);
}

TEST(DriverNoAllocation, DynamixelBusAllocatesNothingInTheTick) {
  std::vector<std::unique_ptr<sim::DynamixelServoSim>> servos;
  std::vector<ActuatorModel> acts = testing::rotary_axes(3);
  for (std::size_t i = 0; i < acts.size(); ++i) {
    acts[i].address = static_cast<int>(i + 1);
    acts[i].encoding = {ActuatorEncoding::Raw::kInt32, 4096.0 / 360.0, 2048.0};
    servos.push_back(std::make_unique<sim::DynamixelServoSim>(static_cast<std::uint8_t>(i + 1)));
  }
  sim::DynamixelPtyWire wire(std::move(servos));
  DynamixelBus bus("dxl", wire.device(), 1'000'000, acts, std::vector<double>(3, 0.0));
  std::vector<double> cmd(3, 2 * kDeg), meas(3);
  std::vector<ActuatorHealth> health(3);
  std::vector<std::uint8_t> on = {1, 0, 1};
  long total = 0;
  for (int k = 0; k < 300; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (k == 100) wire.faults().mute_id = 2;
    total += allocations_in([&] {
      if (k == 50) bus.set_enabled(true);
      if (k == 150) bus.set_actuators_enabled(on);
      bus.read({0, 0.001}, meas);
      bus.read_health(health);
      bus.write({0, 0.001}, cmd);
      (void)bus.status();
      if (k == 299) bus.set_enabled(false);
    });
  }
  EXPECT_GT(wire.requests_of(0x83), 20u) << "sync writes of the goals";
  EXPECT_TRUE(bus.status().fault) << "servo 2 muted";
  EXPECT_EQ(total, 0);
}

TEST(DriverNoAllocation, MaestroBusAllocatesNothingInTheTick) {
  sim::MaestroPtyWire wire(sim::MaestroSim(12));
  std::vector<ActuatorModel> acts = testing::rotary_axes(3);
  for (std::size_t i = 0; i < acts.size(); ++i) {
    acts[i].address = static_cast<int>(i);
    acts[i].encoding = {ActuatorEncoding::Raw::kUint16, 10.0, 1500.0};
  }
  MaestroOptions o;
  o.cycle_period_s = 0.005;
  MaestroBus bus("maestro", wire.device(), 115200, acts, std::vector<double>(3, 0.0), o);
  std::vector<double> cmd(3, 2 * kDeg), meas(3);
  std::vector<ActuatorHealth> health(3);
  std::vector<std::uint8_t> on = {1, 0, 1};
  long total = 0;
  for (int k = 0; k < 300; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (k == 200) wire.faults().mute = true;
    total += allocations_in([&] {
      if (k == 50) bus.set_enabled(true);
      if (k == 150) bus.set_actuators_enabled(on);
      bus.read({0, 0.001}, meas);
      bus.read_health(health);
      bus.write({0, 0.001}, cmd);
      (void)bus.status();
      if (k == 299) bus.set_enabled(false);
    });
  }
  std::uint64_t targets = 0;
  wire.with_maestro([&](sim::MaestroSim& m) { targets = m.commands(0x84); });
  EXPECT_GT(targets, 50u) << "Set Target commands";
  EXPECT_GT(bus.stats().replies, 10u);
  EXPECT_EQ(total, 0);
}

TEST(DriverNoAllocation, FeetechBusAllocatesNothingInTheTick) {
  std::vector<std::unique_ptr<sim::FeetechServoSim>> servos;
  std::vector<ActuatorModel> acts = testing::rotary_axes(3);
  for (std::size_t i = 0; i < acts.size(); ++i) {
    acts[i].address = static_cast<int>(i + 1);
    acts[i].encoding = {ActuatorEncoding::Raw::kUint16, 4096.0 / 360.0, 2048.0};
    servos.push_back(
        std::make_unique<sim::FeetechServoSim>(static_cast<std::uint8_t>(i + 1), ft::Series::kSts));
  }
  sim::FeetechPtyWire wire(std::move(servos));
  FeetechBus bus("ft", wire.device(), 1'000'000, acts, std::vector<double>(3, 0.0));
  std::vector<double> cmd(3, 2 * kDeg), meas(3);
  std::vector<ActuatorHealth> health(3);
  std::vector<std::uint8_t> on = {1, 0, 1};
  long total = 0;
  for (int k = 0; k < 300; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (k == 100) wire.faults().mute_id = 2;
    total += allocations_in([&] {
      if (k == 50) bus.set_enabled(true);
      if (k == 150) bus.set_actuators_enabled(on);
      bus.read({0, 0.001}, meas);
      bus.read_health(health);
      bus.write({0, 0.001}, cmd);
      (void)bus.status();
      if (k == 299) bus.set_enabled(false);
    });
  }
  EXPECT_GT(wire.requests_of(0x83), 5u) << "sync writes of the goals";
  EXPECT_TRUE(bus.status().fault) << "servo 2 muted";
  EXPECT_EQ(total, 0);
}

TEST(DriverNoAllocation, Pca9685BusAllocatesNothingInTheTick) {
  auto i2c = std::make_unique<sim::MemoryI2cBus>();
  i2c->attach(0x40);  // 0x41 stays silent: a fault in the status
  std::vector<ActuatorModel> acts = testing::rotary_axes(4);
  for (auto& a : acts) a.encoding = {ActuatorEncoding::Raw::kUint16, 10.0, 1500.0};
  acts[3].address = 17;
  Pca9685Options o;
  o.boards = {0x40, 0x41};
  o.cycle_period_s = 0.001;
  Pca9685Bus bus("pwm0", std::move(i2c), acts, std::vector<double>(4, 0.0), o);
  std::vector<double> cmd(4, 2 * kDeg), meas(4);
  std::array<std::uint8_t, 4> flags{1, 0, 1, 1};
  long total = 0;
  for (int k = 0; k < 300; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    total += allocations_in([&] {
      if (k == 1) bus.set_enabled(true);
      if (k == 100) bus.set_actuators_enabled(flags);
      bus.read({0, 0.001}, meas);
      bus.write({0, 0.001}, cmd);
      (void)bus.status();
      if (k == 299) bus.set_enabled(false);
    });
  }
  EXPECT_GT(bus.status().frames_sent, 50u);
  EXPECT_TRUE(bus.status().fault);
  EXPECT_EQ(total, 0);
}

}  // namespace
}  // namespace facectl
