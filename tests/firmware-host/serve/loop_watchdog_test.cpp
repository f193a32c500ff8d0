// systemd's watchdog is petted only while the real-time loop ticks.
#include "firmware-host/serve/loop_watchdog.hpp"

#include <gtest/gtest.h>

namespace facectl {
namespace {

using std::chrono::milliseconds;

TEST(LoopWatchdog, LooksOnceAPeriodAndSaysAliveOnlyIfTheTicksMoved) {
  const LoopWatchdog::Clock::time_point t0{};
  LoopWatchdog w(milliseconds(100), t0);
  EXPECT_FALSE(w.look(50, t0 + milliseconds(99)));  // not yet a period
  ASSERT_TRUE(w.look(100, t0 + milliseconds(100)));
  EXPECT_TRUE(w.alive());
  // The loop stalls: the count stays at 100 for the next period.
  EXPECT_FALSE(w.look(100, t0 + milliseconds(150)));
  ASSERT_TRUE(w.look(100, t0 + milliseconds(200)));
  EXPECT_FALSE(w.alive());
  // And resumes.
  ASSERT_TRUE(w.look(101, t0 + milliseconds(300)));
  EXPECT_TRUE(w.alive());
}

TEST(LoopWatchdog, ALoopThatNeverTickedIsDeadAtTheFirstLook) {
  const LoopWatchdog::Clock::time_point t0{};
  LoopWatchdog w(milliseconds(100), t0);
  ASSERT_TRUE(w.look(0, t0 + milliseconds(100)));
  EXPECT_FALSE(w.alive());
}

}  // namespace
}  // namespace facectl
