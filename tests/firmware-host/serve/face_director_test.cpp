// The face command source of `facectl serve`: a change of source never makes
// the command jump, and shows follow their queue, then the neutral face.
#include "firmware-host/serve/face_director.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/realtime/loop_timer.hpp"
#include "tests/firmware-host/serve/served_head.hpp"

namespace facectl {
namespace {

using testing::ServedHead;

TEST(FaceDirector, ASwitchOfSourceCrossfadesInsteadOfJumping) {
  FaceDirector::Pose neutral{};
  LatestValueMailbox<FaceCommand> mailbox;
  FaceDirector director(neutral, mailbox, 250.0);
  director.start();
  FaceDirector::Pose pose{};
  pose[0] = 1.0;
  FaceCommand cmd;
  while (!mailbox.consume(cmd)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  director.hold(FaceDirector::Source::kPose, "", pose);

  // Smoothstep over the crossfade: the steepest slope is 1.5 / crossfade.
  const double max_slope = 1.5 / FaceDirector::kCrossfadeSeconds;
  double steepest = 0.0;
  FaceCommand prev = cmd;
  const std::int64_t until = monotonic_ns() + 1'000'000'000;
  while (monotonic_ns() < until && cmd.values[0] < 1.0) {
    if (mailbox.consume(cmd)) {
      const double dt = static_cast<double>(cmd.stamp_ns - prev.stamp_ns) * 1e-9;
      steepest = std::max(steepest, (cmd.values[0] - prev.values[0]) / dt);
      prev = cmd;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  director.stop();
  EXPECT_DOUBLE_EQ(cmd.values[0], 1.0);  // arrived
  EXPECT_LE(steepest, max_slope * 1.01);
  EXPECT_GT(steepest, max_slope * 0.5);  // it did move, along the curve
}

TEST(FaceDirector, ShowsPlayTheirQueueThenTheNeutralFace) {
  ServedHead h;
  h.shows().write("short.yaml",
                  "show:\n  name: short\n  keyframes:\n    - { t: 0, expression: neutral }\n"
                  "    - { t: 0.3, expression: joy }\n");
  ASSERT_EQ(h.service().play("test", "short", false).status, 200);
  ASSERT_EQ(h.service().play("test", "demo", true).status, 200);
  EXPECT_EQ(h.service().director().status().name, "short");
  ASSERT_TRUE(
      testing::wait_until([&] { return h.service().director().status().name == "demo"; }, 3.0));
  EXPECT_TRUE(h.service().director().status().queue.empty());
  // Queue another short one, then stop: the queue is cleared, neutral follows.
  ASSERT_EQ(h.service().play("test", "short", true).status, 200);
  ASSERT_EQ(h.service().stop_show("test").status, 200);
  const FaceDirector::Status st = h.service().director().status();
  EXPECT_EQ(st.source, FaceDirector::Source::kNeutral);
  EXPECT_TRUE(st.queue.empty());
}

}  // namespace
}  // namespace facectl
