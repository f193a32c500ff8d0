// The real-time tick allocates nothing: this binary counts every malloc,
// calloc, realloc and operator new made while a tick runs, and Eigen's
// runtime no-malloc check turns any Eigen allocation into an assertion.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <new>
#include <thread>

#include "firmware-host/realtime_loop.hpp"
#include "tests/support/sim_head.hpp"

extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
extern "C" void __libc_free(void*);
extern "C" void* __libc_memalign(std::size_t, std::size_t);

namespace {
thread_local bool g_counting = false;
std::atomic<long> g_allocations{0};
void count() {
  if (g_counting) g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

// Interpose the C allocator for the whole process: operator new, std::string,
// std::vector and Eigen all end up here.
extern "C" void* malloc(std::size_t n) {
  count();
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t a, std::size_t b) {
  count();
  return __libc_calloc(a, b);
}
extern "C" void* realloc(void* p, std::size_t n) {
  count();
  return __libc_realloc(p, n);
}
extern "C" void free(void* p) {
  __libc_free(p);
}

namespace facectl {
namespace {

class AllocationGuard {
 public:
  AllocationGuard() {
    g_allocations = 0;
    Eigen::internal::set_is_malloc_allowed(false);
    g_counting = true;
  }
  ~AllocationGuard() {
    g_counting = false;
    Eigen::internal::set_is_malloc_allowed(true);
  }
};

TEST(NoAllocation, TheCountingHookSeesAnAllocation) {
  // The hook itself works: otherwise the test below could never fail.
  long seen = 0;
  {
    AllocationGuard guard;
    auto* p = new std::vector<int>(100);
    seen = g_allocations.load();
    delete p;
  }
  EXPECT_GE(seen, 1);
}

TEST(NoAllocation, EigensRuntimeCheckIsLiveInThisBinary) {
  // With NDEBUG compiled out here, a forbidden Eigen allocation aborts.
  EXPECT_DEATH(
      {
        Eigen::internal::set_is_malloc_allowed(false);
        Eigen::VectorXd v(1000);
        v.setZero();
      },
      "heap allocation is forbidden");
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
      AllocationGuard guard;
      head.step(head.period());
      total += g_allocations.load();
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
  head.controller().request_enable();
  run(1.5);
  for (int k = 1; k <= head.model().safety.overrun_fault_count; ++k) {
    AllocationGuard guard;
    head.step(head.period(), k);
    total += g_allocations.load();
    ++ticks;
  }
  EXPECT_EQ(head.controller().state(), SafetyState::kFault);
  EXPECT_EQ(total, 0) << "allocations in " << ticks << " ticks";
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
    Eigen::internal::set_is_malloc_allowed(false);
    g_allocations = 0;
    g_counting = true;
    loop.run(stop);
    g_counting = false;
    seen = g_allocations.load();
    Eigen::internal::set_is_malloc_allowed(true);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  stop = true;
  rt.join();
  EXPECT_GT(stats.ticks.load(), 100u);
  EXPECT_EQ(seen, 0);
}

}  // namespace
}  // namespace facectl
