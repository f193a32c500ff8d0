// The real-time tick allocates nothing: this binary counts every malloc,
// calloc, realloc, aligned allocation and operator new made while a tick runs.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <new>
#include <thread>

#include "firmware-host/run/realtime_loop.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/sim_head.hpp"
#include "tests/support/text_files.hpp"

namespace facectl {
namespace {

using testing::begin_counting_allocations;
using testing::end_counting_allocations;

// Counts this thread's allocations while alive.
class AllocationGuard {
 public:
  AllocationGuard() { begin_counting_allocations(); }
  ~AllocationGuard() { counted_ = end_counting_allocations(); }
  static long last() { return counted_; }

 private:
  static inline long counted_ = 0;
};

TEST(NoAllocation, TheCountingHookSeesAnAllocation) {
  // The hook itself works: otherwise the test below could never fail.
  long seen = 0;
  std::vector<int>* p = nullptr;
  {
    AllocationGuard guard;
    p = new std::vector<int>(100);
  }
  seen = AllocationGuard::last();
  delete p;
  EXPECT_GE(seen, 1);
}

TEST(NoAllocation, TheCountingHookSeesAnEigenAllocation) {
  // Eigen's heap path (its aligned malloc) reaches the hook too.
  long seen = 0;
  double sum = 0.0;
  {
    AllocationGuard guard;
    Eigen::VectorXd v = Eigen::VectorXd::Ones(1000);
    sum = v.sum();
  }
  seen = AllocationGuard::last();
  EXPECT_EQ(sum, 1000.0);
  EXPECT_GE(seen, 1);
}

TEST(NoAllocation, TicksInEveryStateAllocateNothing) {
  testing::SimHead head(default_config_path(), 1 << 14);
  auto cmd = head.model().neutral;
  head.controller().request_enable();
  // Warm up outside the guard: first-touch effects are not the tick's concern.
  head.send(cmd);
  head.step(head.period());

  long total = 0;
  long ticks = 0;
  auto run = [&](double seconds) {
    const long n = static_cast<long>(seconds / head.period());
    for (long i = 0; i < n; ++i) {
      cmd[static_cast<std::size_t>(i) % head.model().layout.muscle_count()] =
          static_cast<double>(i % 7) / 7.0;
      head.send(cmd);
      {
        AllocationGuard guard;
        head.step(head.period());
      }
      total += AllocationGuard::last();
      ++ticks;
    }
    while (head.telemetry()->front() != nullptr) head.telemetry()->pop();
  };
  run(1.5);  // ENABLING then RUNNING
  EXPECT_EQ(head.controller().state(), SafetyState::kRunning);
  head.hardware().io.press_estop();
  run(0.1);  // ESTOP
  EXPECT_EQ(head.controller().state(), SafetyState::kEstop);
  head.hardware().io.release_estop();
  head.controller().request_reset();
  head.controller().request_enable();
  run(1.5);
  head.controller().request_shutdown();
  run(1.0);  // STOPPING then IDLE
  EXPECT_EQ(head.controller().state(), SafetyState::kIdle);
  // The fault paths: a bus fault, then an overrun storm, each logged with its detail.
  head.controller().request_enable();
  run(1.5);
  head.hardware().find("can0")->inject_fault("bus-off");
  run(0.05);
  EXPECT_EQ(head.controller().state(), SafetyState::kFault);
  head.hardware().find("can0")->clear_fault();
  head.controller().request_reset();
  run(0.01);
  EXPECT_EQ(head.controller().state(), SafetyState::kIdle);
  // FAULT that holds the jaw (its struts hold): can0 stays driven after a
  // modbus0 fault, then relaxes when can0 faults too.
  head.controller().request_enable();
  run(1.5);
  head.hardware().find("modbus0")->inject_fault("board 3 not answering");
  run(0.3);
  EXPECT_TRUE(head.hardware().find("can0")->enabled());
  head.hardware().find("can0")->inject_fault("bus-off");
  run(0.05);
  EXPECT_FALSE(head.hardware().find("can0")->enabled());
  head.hardware().find("can0")->clear_fault();
  head.hardware().find("modbus0")->clear_fault();
  head.controller().request_reset();
  head.controller().request_enable();
  run(1.5);
  for (int k = 1; k <= head.model().safety.overrun_fault_count; ++k) {
    {
      AllocationGuard guard;
      head.step(head.period(), k);
    }
    total += AllocationGuard::last();
    ++ticks;
  }
  EXPECT_EQ(head.controller().state(), SafetyState::kFault);
  EXPECT_EQ(total, 0) << "allocations in " << ticks << " ticks";
}

TEST(NoAllocation, DriveProtectionTicksAllocateNothing) {
  // The hobby DYNAMIXEL rig configures protection on every actuator: derate,
  // a temperature FAULT (its event text written in the tick), reset, and a
  // hardware-error FAULT, all under the guard.
  ConfigOverrides o;
  o.rig_path = testing::source_path("config/rigs/hobby_dynamixel.yaml").string();
  OfflineHead head(load_config(default_config_path(), o), 1 << 14);
  ASSERT_TRUE(head.model().protection.at(1).configured);
  auto cmd = head.model().neutral;
  head.controller().request_enable();
  head.send(cmd);
  head.step(head.period());
  SimActuatorBus& bus = *head.hardware().find("servos");
  long total = 0;
  auto run = [&](double seconds) {
    for (long i = 0; i < static_cast<long>(seconds / head.period()); ++i) {
      cmd[static_cast<std::size_t>(i) % head.model().layout.muscle_count()] =
          static_cast<double>(i % 7) / 7.0;
      head.send(cmd);
      {
        AllocationGuard guard;
        head.step(head.period());
      }
      total += AllocationGuard::last();
    }
    while (head.telemetry()->front() != nullptr) head.telemetry()->pop();
    while (head.events().front() != nullptr) head.events().pop();
  };
  run(1.5);
  ASSERT_EQ(head.controller().state(), SafetyState::kRunning);
  ActuatorHealth h;
  h.temperature_c = 65.0;
  bus.script_health(1, h);
  run(0.5);
  EXPECT_LT(head.controller().protection(1).factor, 1.0);
  h.temperature_c = 71.0;
  bus.script_health(1, h);
  run(0.2);
  EXPECT_EQ(head.controller().state(), SafetyState::kFault);
  h = ActuatorHealth{};
  bus.script_health(1, h);
  head.controller().request_reset();
  run(0.01);
  EXPECT_EQ(head.controller().state(), SafetyState::kIdle);
  head.controller().request_enable();
  run(1.5);
  ASSERT_EQ(head.controller().state(), SafetyState::kRunning);
  h.hardware_error = 4;
  bus.script_health(2, h);
  run(0.1);
  EXPECT_EQ(head.controller().state(), SafetyState::kFault);
  EXPECT_EQ(total, 0);
}

// The whole real-time loop (timer, histograms, tick) on a real thread.
TEST(NoAllocation, TheRealTimeLoopAllocatesNothing) {
  testing::SimHead head(default_config_path(), 1 << 14);
  head.controller().request_enable();
  LoopStats stats;
  RealtimeLoop loop(head.controller(), head.model().rate_hz, stats);
  std::atomic<bool> stop{false};
  long seen = -1;
  std::thread rt([&] {
    begin_counting_allocations();
    loop.run(stop);
    seen = end_counting_allocations();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  stop = true;
  rt.join();
  EXPECT_GT(stats.ticks.load(), 100u);
  EXPECT_EQ(seen, 0);
}

}  // namespace
}  // namespace facectl
