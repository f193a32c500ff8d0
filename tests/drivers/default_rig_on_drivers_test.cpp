// The shipped default rig driven by the real Controller through the real
// drivers, in real time: its 12 CAN axes through CustomCanBus (4 simulated
// boards on the in-process CAN wire) and its 14 Modbus servos through
// ModbusBus (2 simulated boards behind a libmodbus TCP server on 127.0.0.1).
// Each fault lands in FAULT or ESTOP with its reason, within its documented
// bound (docs/PROTOCOLS.md), and nothing is commanded after the e-stop.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "control/clock.hpp"
#include "control/controller.hpp"
#include "drivers/can/custom_can_bus.hpp"
#include "drivers/modbus/modbus_bus.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/custom_can_board_sim.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "sim/devices/modbus_board_server.hpp"
#include "sim/devices/sim_safety_io.hpp"
#include "tests/drivers/can_test_axes.hpp"

namespace facectl {
namespace {

using namespace std::chrono_literals;

class Sniffer final : public sim::CanDevice {
 public:
  void on_frame(const CanFrame& f, std::int64_t) override {
    if (f.id > custom_can::kCommandBase && f.id <= custom_can::kCommandBase + 63) ++commands;
  }
  void step(std::int64_t) override {}
  std::atomic<std::uint64_t> commands{0};
};

std::vector<sim::BoardChannel> channels(const std::vector<ActuatorModel>& acts, std::size_t first,
                                        std::size_t count) {
  std::vector<sim::BoardChannel> c(count);
  for (std::size_t i = 0; i < count; ++i) {
    c[i].plant = testing::fast_plant();
    c[i].unit = acts[first + i].kind == ActuatorKind::kRotary ? modbus_map::Unit::kRotary
                                                              : modbus_map::Unit::kLinear;
    c[i].initial = acts[first + i].rest;       // a powered-down head sits at rest
    c[i].encoding = acts[first + i].encoding;  // the board reads what the rig says
  }
  return c;
}

std::vector<double> rests(const std::vector<ActuatorModel>& acts) {
  std::vector<double> r;
  for (const ActuatorModel& a : acts) r.push_back(a.rest);
  return r;
}

class DefaultRigOnDrivers : public ::testing::Test {
 protected:
  DefaultRigOnDrivers() : config_(load_config(default_config_path())), model_(config_.built.model) {
    const BusModel& can = model_.buses[0];
    const BusModel& mb = model_.buses[1];
    std::vector<ActuatorModel> can_acts(
        model_.actuators.begin() + static_cast<long>(can.first),
        model_.actuators.begin() + static_cast<long>(can.first + can.count));
    std::vector<ActuatorModel> mb_acts(
        model_.actuators.begin() + static_cast<long>(mb.first),
        model_.actuators.begin() + static_cast<long>(mb.first + mb.count));
    std::vector<sim::CanDevice*> devices{&sniffer_};
    for (int n = 0; n < 4; ++n) {
      boards_.push_back(std::make_unique<sim::CustomCanBoardSim>(
          n + 1, channels(can_acts, static_cast<std::size_t>(3 * n), 3),
          custom_can::Width::kInt16));
      devices.push_back(boards_.back().get());
    }
    net_ = std::make_unique<sim::CanDeviceNetwork>(link_.devices(), devices);
    can_bus_ = std::make_unique<CustomCanBus>("can0", link_.host(), can_acts, rests(can_acts));
    mb1_ = std::make_unique<sim::ModbusActuatorBoard>(1, channels(mb_acts, 0, 8));
    mb2_ = std::make_unique<sim::ModbusActuatorBoard>(2, channels(mb_acts, 8, 6));
    server_ = sim::ModbusBoardServer::tcp({mb1_.get(), mb2_.get()});
    ModbusEndpoint ep;
    ep.port = server_->port();
    modbus_bus_ = std::make_unique<ModbusBus>("modbus0", ep, mb_acts, rests(mb_acts));
    seams_ = {can_bus_.get(), modbus_bus_.get()};
    controller_ = std::make_unique<Controller>(model_, seams_, io_,
                                               ControllerChannels{&mailbox_, nullptr, &events_});
    pose_ = model_.neutral;
    pose_[model_.layout.jaw_pitch()] = 0.1;
  }

  // Real-time 1 kHz ticks until `done` or `limit`; the CAN devices run after
  // each tick. Returns the seconds taken, or -1; ticks_ counts the ticks run,
  // and first_ns_, previous_ns_ and last_ns_ keep the clock of the first, the
  // next-to-last and the last of them.
  template <typename Done>
  double run(std::chrono::milliseconds limit, Done done) {
    ticks_ = 0;
    const auto t0 = std::chrono::steady_clock::now();
    auto next = t0;
    while (std::chrono::steady_clock::now() - t0 < limit) {
      next += 1ms;
      std::this_thread::sleep_until(next);
      TickTiming t;
      t.tick = tick_++;
      t.now_ns = monotonic_ns();
      t.dt_s = 0.001;
      if (ticks_ == 0) first_ns_ = t.now_ns;
      previous_ns_ = last_ns_;
      last_ns_ = t.now_ns;
      FaceCommand cmd;
      cmd.values = pose_;
      cmd.sequence = tick_;
      cmd.stamp_ns = t.now_ns;
      mailbox_.publish(cmd);
      controller_->tick(t);
      ++ticks_;
      net_->poll(t.now_ns);
      if (done())
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    return -1.0;
  }

  void enable() {
    controller_->request_enable();
    ASSERT_GT(run(5000ms, [&] { return controller_->state() == SafetyState::kRunning; }), 0.0)
        << "state " << to_string(controller_->state()) << ", last event " << last_event().detail;
  }

  TransitionEvent last_event() {
    TransitionEvent ev;
    while (const TransitionEvent* e = events_.front()) {
      ev = *e;
      events_.pop();
    }
    return ev;
  }

  // The bus-off bound counts ticks (the CAN bus reads its errors in the tick);
  // the Modbus ones count seconds (its I/O thread lives in wall time).
  void expect_fault(const char* reason, double bound_s, int bound_ticks,
                    const std::function<void()>& inject) {
    enable();
    inject();
    const double t = run(3000ms, [&] { return controller_->state() == SafetyState::kFault; });
    ASSERT_GT(t, 0.0) << "no FAULT";
    if (bound_s > 0) {
      EXPECT_LE(t, bound_s);
    }
    if (bound_ticks > 0) {
      EXPECT_LE(ticks_, bound_ticks);
    }
    const TransitionEvent ev = last_event();
    EXPECT_EQ(ev.reason, TransitionReason::kBusFault);
    if (reason != nullptr) {
      EXPECT_STREQ(ev.detail, reason);
    } else {
      EXPECT_NE(std::string(ev.detail).find(": not answering within 20 ms"), std::string::npos)
          << ev.detail;
    }
    std::printf("FAULT '%s' after %.3f s, %d ticks\n", ev.detail, t, ticks_);
  }

  LoadedConfig config_;
  const ControllerModel& model_;
  MemoryCanLink link_{4096};
  Sniffer sniffer_;
  std::vector<std::unique_ptr<sim::CustomCanBoardSim>> boards_;
  std::unique_ptr<sim::CanDeviceNetwork> net_;
  std::unique_ptr<CustomCanBus> can_bus_;
  std::unique_ptr<sim::ModbusActuatorBoard> mb1_, mb2_;
  std::unique_ptr<sim::ModbusBoardServer> server_;
  std::unique_ptr<ModbusBus> modbus_bus_;
  std::vector<ActuatorBus*> seams_;
  SimSafetyIo io_;
  LatestValueMailbox<FaceCommand> mailbox_;
  SpscRing<TransitionEvent> events_{256};
  std::unique_ptr<Controller> controller_;
  std::array<double, kMaxFaceSignals> pose_{};
  std::uint64_t tick_ = 0;
  int ticks_ = 0;
  std::int64_t first_ns_ = 0, previous_ns_ = 0, last_ns_ = 0;
};

TEST_F(DefaultRigOnDrivers, TheHeadRunsAndTheBoardsFollowTheController) {
  enable();
  run(500ms, [] { return false; });
  // The jaw opened toward 0.1 rad (5.7 degrees): the digastric strut (actuator
  // 0) shortens about 1.67 mm a degree from its 35 mm rest.
  const double jaw = controller_->commands()[0];
  EXPECT_LT(jaw, model_.actuators[0].rest - 0.005);
  EXPECT_NEAR(boards_[0]->position(0), jaw, 0.005);
  EXPECT_TRUE(mb1_->enabled());
  EXPECT_FALSE(can_bus_->status().fault) << can_bus_->status().reason;
  EXPECT_FALSE(modbus_bus_->status().fault) << modbus_bus_->status().reason;
}

TEST_F(DefaultRigOnDrivers, AnEstopStopsEveryCommandOnTheTickItIsRead) {
  enable();
  io_.press_estop();
  ASSERT_GT(run(10ms, [&] { return controller_->state() == SafetyState::kEstop; }), 0.0);
  EXPECT_FALSE(io_.power_enabled());
  std::this_thread::sleep_for(20ms);  // a Modbus cycle already in flight completes
  const std::uint64_t can_commands = sniffer_.commands.load();
  const std::uint64_t mb_targets = mb1_->target_writes() + mb2_->target_writes();
  run(300ms, [] { return false; });
  EXPECT_EQ(sniffer_.commands.load(), can_commands) << "CAN commands after the e-stop";
  EXPECT_EQ(mb1_->target_writes() + mb2_->target_writes(), mb_targets)
      << "Modbus targets after the e-stop";
  EXPECT_FALSE(mb1_->enabled());
  EXPECT_FALSE(mb2_->enabled());
}

TEST_F(DefaultRigOnDrivers, ASilentModbusBoard) {
  // 100 ms board timeout + one worst-case cycle (160 ms) + the tick that reads it.
  expect_fault("modbus0 board 2: not answering within 20 ms", 0.261, 0, [&] {
    server_->faults().only_unit = 2;
    server_->faults().silent = true;
  });
}

TEST_F(DefaultRigOnDrivers, AModbusTimeoutStorm) {
  // Every reply later than the 20 ms response timeout.
  // The whole bus is late: whichever board's timeout runs out first names itself.
  expect_fault(nullptr, 0.261, 0, [&] { server_->faults().delay_us = 30'000; });
}

TEST_F(DefaultRigOnDrivers, CanBusOff) {
  expect_fault("can0: bus-off", 0, 1, [&] { link_.host().inject_error(CanError::kBusOff); });
}

TEST_F(DefaultRigOnDrivers, ALostCanBoardHeartbeat) {
  ASSERT_NO_FATAL_FAILURE(expect_fault("can0 board 3: heartbeat lost", 0, 0,
                                       [&] { boards_[2]->faults().silent = true; }));
  // The board answers every command, so the bus last heard it on the first
  // tick after it fell silent. The 100 ms timeout runs on the bus's clock, so
  // it is checked there: the fault comes on the first tick past it. (Counted
  // in ticks it is not a bound: a tick late under load is followed by ticks
  // that catch up, and 102 ticks was the usual count.)
  constexpr std::int64_t kTimeoutNs = 100'000'000;
  EXPECT_GT(last_ns_ - first_ns_, kTimeoutNs) << "faulted before the timeout";
  EXPECT_LE(previous_ns_ - first_ns_, kTimeoutNs) << "the tick before the fault was past it";
}

}  // namespace
}  // namespace facectl
