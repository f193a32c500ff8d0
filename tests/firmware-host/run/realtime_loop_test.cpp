// The loop's statistics add up over runs: `bench loop` runs the pipeline in
// chunks with one LoopStats, and reported only the last chunk's overruns.
#include "firmware-host/run/realtime_loop.hpp"

#include <gtest/gtest.h>

#include <thread>

#include "firmware-host/run/offline_head.hpp"

namespace facectl {
namespace {

// Runs the loop on its own thread for `seconds`, the first tick stalled for
// `stall_ms` (the loop's own stall hook, as `--inject overrun_storm`). The
// stall is set on the loop's thread, just before it runs: set before the
// thread started, part of it passed while the thread was being started, and
// on a busy CI machine the second run then missed only 2 deadlines.
void run_once(Controller& controller, LoopStats& stats, double stall_ms, double seconds) {
  RealtimeLoop loop(controller, 1000.0, stats);
  std::atomic<bool> stop{false};
  std::thread t([&] {
    loop.stall_until(monotonic_ns() + static_cast<std::int64_t>(stall_ms * 1e6));
    loop.run(stop);
  });
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  stop.store(true);
  t.join();
}

TEST(RealtimeLoop, StatsAddUpOverRuns) {
  OfflineHead head(load_config(default_config_path(), {}));
  LoopStats stats;
  run_once(head.controller(), stats, 8.0, 0.05);
  const std::uint64_t first_overruns = stats.overruns.load();
  const std::uint64_t first_skipped = stats.skipped.load();
  ASSERT_GE(first_overruns, 1u);
  ASSERT_GE(first_skipped, 3u);
  // The second run's stall adds to the first's (an 8 ms stall at 1 kHz
  // misses about 8 deadlines; only 3 are counted on).
  run_once(head.controller(), stats, 8.0, 0.05);
  EXPECT_GE(stats.overruns.load(), first_overruns + 1);
  EXPECT_GE(stats.skipped.load(), first_skipped + 3);
}

}  // namespace
}  // namespace facectl
