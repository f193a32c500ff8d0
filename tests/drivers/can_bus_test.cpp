// The CAN actuator buses (CiA 402 and the custom layout) against simulated
// drives and boards on the in-process CAN wire, in simulated time: 1 ms ticks,
// host first (read, write), then the devices. Bounds are docs/PROTOCOLS.md's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "drivers/bus_factory.hpp"
#include "drivers/can/cia402_bus.hpp"
#include "drivers/can/custom_can_bus.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/custom_can_board_sim.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "tests/drivers/can_test_axes.hpp"
#include "tests/drivers/can_test_rig.hpp"

namespace facectl {
namespace {

using testing::Cia402;
using testing::fast_plant;
using testing::kDeg;
using testing::kMs;
using testing::Rig;
using testing::Sniffer;
const auto rotary = testing::rotary_axes;

TEST_F(Cia402, DrivesAreConfiguredBySdoReachOperationEnabledAndFollowTheTargets) {
  enable();
  for (const auto& d : drives_) {
    EXPECT_EQ(d->nmt(), cia402::NmtState::kOperational);
    EXPECT_EQ(d->mode(), 8);  // cyclic synchronous position
    EXPECT_EQ(d->limit_max(), std::lround(30 * kDeg * options_.rotary_counts_per_rad));
    EXPECT_EQ(d->limit_min(), -std::lround(30 * kDeg * options_.rotary_counts_per_rad));
  }
  rig_->until([] { return false; }, 200, 10 * kDeg);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(drives_[i]->position(), 10 * kDeg, 0.01 * kDeg);
    EXPECT_NEAR(rig_->measured()[i], 10 * kDeg, 0.01 * kDeg);
  }
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(Cia402, TheDrivesOwnLimitsHoldEvenIfTheHostCommandsBeyondThem) {
  enable();
  rig_->until([] { return false; }, 300, 45 * kDeg);
  EXPECT_NEAR(drives_[0]->position(), 30 * kDeg, 0.01 * kDeg);
}

TEST_F(Cia402, ALostHeartbeatFaultsWithinTheTimeoutPlusTwoTicks) {
  enable();
  drives_[1]->faults().silent = true;
  const int ms = rig_->until([&] { return bus_->status().fault; }, 1000);
  ASSERT_GT(ms, 0);
  EXPECT_LE(ms, static_cast<int>(options_.heartbeat_timeout_s * 1000) + 2);
  EXPECT_STREQ(bus_->status().reason, "can0 drive 2: heartbeat lost");
}

TEST_F(Cia402, AnEmcyFaultsWithItsCodeOnTheNextTick) {
  enable();
  drives_[2]->inject_fault(0x2310);
  const int ms = rig_->until([&] { return bus_->status().fault; }, 100);
  ASSERT_GT(ms, 0);
  EXPECT_LE(ms, 2);
  EXPECT_STREQ(bus_->status().reason, "can0 drive 3: emergency (EMCY)");
  EXPECT_EQ(bus_->last_emcy(2), 0x2310);
}

TEST_F(Cia402, BusOffAndErrorPassiveFaultWithTheirReasonOnTheNextRead) {
  enable();
  link_.host().inject_error(CanError::kBusOff);
  rig_->tick(0.0);
  EXPECT_STREQ(bus_->status().reason, "can0: bus-off");
  link_.host().inject_error(CanError::kRestarted);
  rig_->tick(0.0);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
  link_.host().inject_error(CanError::kErrorPassive);
  rig_->tick(0.0);
  EXPECT_STREQ(bus_->status().reason, "can0: error-passive");
}

TEST_F(Cia402, DisablingSendsQuickStopThenDisableVoltageThenNothing) {
  enable();
  rig_->until([] { return false; }, 50, 5 * kDeg);
  bus_->set_enabled(false);  // the ESTOP tick: quick stop goes out on it
  rig_->tick(20 * kDeg, false);
  for (const auto& d : drives_) {
    EXPECT_EQ(d->last_controlword(), cia402::kCwQuickStop);
    EXPECT_EQ(d->quick_stops(), 1u);
    EXPECT_EQ(d->state(), cia402::DriveState::kQuickStopActive);
  }
  // Held for quick_stop_s (this drive stays in quick stop active), then
  // disable voltage: torque off, in that order.
  const int ms =
      rig_->until([&] { return drives_[0]->last_controlword() == cia402::kCwDisableVoltage; }, 1000,
                  20 * kDeg, false);
  EXPECT_NEAR(ms, options_.quick_stop_s * 1000, 2);
  for (const auto& d : drives_) EXPECT_EQ(d->state(), cia402::DriveState::kSwitchOnDisabled);
  const std::uint64_t seen = sniffer_.frames;
  const std::uint64_t sent = bus_->status().frames_sent;
  rig_->until([] { return false; }, 300, 20 * kDeg, false);
  EXPECT_EQ(sniffer_.frames, seen) << "silent once the stop sequence is through";
  EXPECT_EQ(bus_->status().frames_sent, sent);
  EXPECT_NEAR(drives_[0]->position(), 5 * kDeg, 0.05 * kDeg);  // it stopped where it was
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(Cia402, ReEnablingResetsDriveFaultsAndWalksBackToOperationEnabled) {
  enable();
  bus_->set_enabled(false);
  rig_->until([] { return false; }, 200, 0.0, false);
  drives_[0]->inject_fault(0x2310);  // while off: nobody resets it
  rig_->until([] { return false; }, 5, 0.0, false);
  ASSERT_EQ(drives_[0]->state(), cia402::DriveState::kFault);
  enable();
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(Cia402, ADriveSwitchedOffAloneGetsDisableVoltageWhileTheOthersRun) {
  enable();
  rig_->until([] { return false; }, 200, 10 * kDeg);
  std::array<std::uint8_t, 3> on{1, 0, 1};
  bus_->set_actuators_enabled(on);
  rig_->until([] { return false; }, 300, -10 * kDeg);
  EXPECT_EQ(drives_[1]->state(), cia402::DriveState::kSwitchOnDisabled);
  EXPECT_EQ(drives_[1]->quick_stops(), 1u) << "quick stop first, then disable voltage";
  EXPECT_NEAR(drives_[1]->position(), 10 * kDeg, 0.05 * kDeg) << "torque off: not commanded";
  for (const std::size_t i : {0u, 2u}) {
    EXPECT_EQ(drives_[i]->state(), cia402::DriveState::kOperationEnabled);
    EXPECT_NEAR(drives_[i]->position(), -10 * kDeg, 0.01 * kDeg);
  }
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
  // Switched on again: the drive walks back, holding where it is until enabled.
  on = {1, 1, 1};
  bus_->set_actuators_enabled(on);
  ASSERT_GT(rig_->until([&] { return all_enabled(); }, 200, -10 * kDeg), 0);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(Cia402, AFullTxQueueRefusesFramesWithoutBlockingAndThenFaults) {
  MemoryCanLink tiny(4);  // nobody drains it
  Cia402Bus bus("can1", tiny.host(), rotary(3), std::vector<double>(3, 0.0), options_);
  bus.set_enabled(true);
  std::vector<double> cmd(3, 0.0), meas(3);
  std::int64_t now = kMs;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < 60; ++k) {
    now += kMs;
    bus.read({now, 0.001}, meas);
    bus.write({now, 0.001}, cmd);
  }
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(50));
  EXPECT_STREQ(bus.status().reason, "can1: TX queue full");
}

TEST(CanBudget, TheDefaultRigsTwelveCanAxesFitOnlyPackedAndBelow1kHz) {
  MemoryCanLink link;
  std::vector<ActuatorModel> axes = rotary(12);
  const Cia402Bus cia("can0", link.host(), axes, std::vector<double>(12, 0.0));
  // SYNC + 12 RPDO + 12 TPDO + heartbeats: far above 70% at 1 kHz.
  EXPECT_EQ(cia.budget(1000.0, 1'000'000).frames_per_cycle, 26);
  EXPECT_TRUE(cia.budget(1000.0, 1'000'000).refused());
  const CustomCanBus custom("can0", link.host(), axes, std::vector<double>(12, 0.0));
  EXPECT_EQ(custom.board_count(), 4u);
  EXPECT_TRUE(custom.budget(1000.0, 1'000'000).refused());  // 8 frames at 1 kHz = 108%
  CanBusOptions slow;
  slow.cycle_divider = 4;
  const CustomCanBus quarter("can0", link.host(), axes, std::vector<double>(12, 0.0), slow);
  EXPECT_NEAR(quarter.budget(1000.0, 1'000'000).load, 0.27, 1e-12);
  EXPECT_FALSE(quarter.budget(1000.0, 1'000'000).warned());
}

TEST(BusFactory, ARigAbove70PercentIsRefusedWithItsBudgetBeforeTheBusIsOpened) {
  BusSpec spec{"can0", "can", "no-such-can", 1'000'000, "cia402", {}, {}, {}, {}, {}, {}};
  try {
    make_bus(spec, rotary(12), std::vector<double>(12, 0.0), 1000.0);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("can0: 26 frames per cycle at 1000 Hz"), std::string::npos)
        << e.what();
  }
  // Within budget, the next problem is the missing interface, named.
  spec.can_protocol = "custom";
  spec.can.cycle_divider = 4;
  try {
    make_bus(spec, rotary(12), std::vector<double>(12, 0.0), 1000.0);
    FAIL() << "opened a missing interface";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("SocketCAN no-such-can"), std::string::npos) << e.what();
  }
}

class CustomCan : public ::testing::Test {
 protected:
  CustomCan() {
    for (int n = 1; n <= 4; ++n) {
      std::vector<sim::BoardChannel> ch(3);
      for (auto& c : ch) c.plant = fast_plant();
      boards_.push_back(std::make_unique<sim::CustomCanBoardSim>(n, ch, custom_can::Width::kInt16));
    }
    net_ = std::make_unique<sim::CanDeviceNetwork>(
        link_.devices(),
        std::vector<sim::CanDevice*>{boards_[0].get(), boards_[1].get(), boards_[2].get(),
                                     boards_[3].get(), &sniffer_});
    bus_ = std::make_unique<CustomCanBus>("can0", link_.host(), rotary(12),
                                          std::vector<double>(12, 0.0));
    rig_ = std::make_unique<Rig<CustomCanBus>>(*bus_, *net_, 12);
  }
  MemoryCanLink link_{1024};
  std::vector<std::unique_ptr<sim::CustomCanBoardSim>> boards_;
  Sniffer sniffer_;
  std::unique_ptr<sim::CanDeviceNetwork> net_;
  std::unique_ptr<CustomCanBus> bus_;
  std::unique_ptr<Rig<CustomCanBus>> rig_;
};

TEST_F(CustomCan, BoardsFollowPackedTargetsWithAnUnbrokenSequence) {
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 200, -7 * kDeg);
  for (const auto& b : boards_) {
    EXPECT_TRUE(b->enabled());
    EXPECT_NEAR(b->position(2), -7 * kDeg, 0.01 * kDeg);
    EXPECT_EQ(b->commands(), 200u);
    EXPECT_EQ(b->sequence_gaps(), 0u);
  }
  EXPECT_NEAR(rig_->measured()[11], -7 * kDeg, 0.01 * kDeg);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(CustomCan, ASilentBoardFaultsWithinTheHeartbeatTimeoutPlusTwoTicks) {
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 20);
  boards_[3]->faults().silent = true;
  const int ms = rig_->until([&] { return bus_->status().fault; }, 1000);
  ASSERT_GT(ms, 0);
  EXPECT_LE(ms, 102);  // timeout + 2 ticks: the last reply is read one tick after it is sent
  EXPECT_STREQ(bus_->status().reason, "can0 board 4: heartbeat lost");
}

TEST_F(CustomCan, ABoardFaultAndCorruptFramesAreToldApart) {
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 20, 3 * kDeg);
  boards_[0]->faults().corrupt_next = 5;
  rig_->until([] { return false; }, 10, 3 * kDeg);
  EXPECT_EQ(bus_->bad_frames(), 5u);
  EXPECT_FALSE(bus_->status().fault) << "a few short frames are not a fault by themselves";
  EXPECT_NEAR(rig_->measured()[0], 3 * kDeg, 0.5 * kDeg);  // never decoded from a short frame
  boards_[1]->inject_fault();
  ASSERT_GT(rig_->until([&] { return bus_->status().fault; }, 5), 0);
  EXPECT_STREQ(bus_->status().reason, "can0 board 2: reports a fault");
}

TEST_F(CustomCan, ABoardWithAnActuatorSwitchedOffIsDisabledWhileTheOthersRun) {
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 100, 3 * kDeg);
  // Address 5 (board 2, channel 1) relaxes: the enable flag is per board.
  std::array<std::uint8_t, 12> on{};
  on.fill(1);
  on[4] = 0;
  bus_->set_actuators_enabled(on);
  // Its board-mates are switched off with it, and the flags say so.
  EXPECT_EQ(on[3], 0);
  EXPECT_EQ(on[5], 0);
  EXPECT_EQ(std::count(on.begin(), on.end(), std::uint8_t{1}), 9);
  const std::uint64_t board2_commands = boards_[1]->commands();
  rig_->until([] { return false; }, 200, 8 * kDeg);
  EXPECT_FALSE(boards_[1]->enabled());
  EXPECT_GT(boards_[1]->commands(), board2_commands) << "its frames (heartbeat) go on";
  EXPECT_FALSE(boards_[1]->watchdog_tripped());
  for (std::size_t ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(boards_[1]->position(ch), 3 * kDeg, 0.05 * kDeg) << ch;
  }
  for (const std::size_t b : {0u, 2u, 3u}) {
    EXPECT_TRUE(boards_[b]->enabled());
    EXPECT_NEAR(boards_[b]->position(0), 8 * kDeg, 0.01 * kDeg);
  }
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(CustomCan, DisabledSendsNothingAndTheBoardsWatchdogDropsThem) {
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 20);
  bus_->set_enabled(false);
  const std::uint64_t seen = sniffer_.frames;
  rig_->until([] { return false; }, 100);
  EXPECT_EQ(sniffer_.frames, seen);
  for (const auto& b : boards_) {
    EXPECT_FALSE(b->enabled());
    EXPECT_TRUE(b->watchdog_tripped());
  }
  EXPECT_FALSE(bus_->status().fault) << "a watchdog trip while disabled is expected";
  // Re-enabling clears the latched watchdog with the fault-reset flag.
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 20);
  EXPECT_TRUE(boards_[0]->enabled());
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

}  // namespace
}  // namespace facectl
