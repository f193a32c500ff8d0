#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "control/realtime/spsc_ring.hpp"

namespace facectl {
namespace {

TEST(LatestValueMailbox, IsLockFree) {
  EXPECT_TRUE(LatestValueMailbox<FaceCommand>::is_lock_free());
}

TEST(LatestValueMailbox, DeliversOnlyNewValuesAndTheNewestOne) {
  LatestValueMailbox<int> box;
  int out = -1;
  EXPECT_FALSE(box.consume(out));
  box.publish(1);
  box.publish(2);
  EXPECT_TRUE(box.consume(out));
  EXPECT_EQ(out, 2);
  EXPECT_FALSE(box.consume(out));
  EXPECT_EQ(out, 2);
}

// A producer and a consumer at full speed: the consumer never sees a torn
// command (all values equal the sequence) nor a sequence going backwards.
TEST(LatestValueMailbox, NeverTearsAValueUnderConcurrentUse) {
  LatestValueMailbox<FaceCommand> box;
  std::atomic<bool> done{false};
  std::thread producer([&] {
    FaceCommand c;
    for (std::uint64_t s = 1; s <= 300000; ++s) {
      c.sequence = s;
      c.values.fill(static_cast<double>(s));
      box.publish(c);
    }
    done = true;
  });
  FaceCommand got;
  std::uint64_t last = 0;
  long reads = 0;
  for (;;) {
    const bool finished = done.load();  // read before consuming: the last value is not missed
    if (!box.consume(got)) {
      if (finished) break;
      continue;
    }
    ++reads;
    for (double v : got.values) ASSERT_EQ(v, static_cast<double>(got.sequence));
    ASSERT_GT(got.sequence, last);
    last = got.sequence;
  }
  producer.join();
  EXPECT_GT(reads, 0);
  EXPECT_EQ(last, 300000u);
}

TEST(SpscRing, RefusesAndCountsWhenFullInsteadOfBlocking) {
  SpscRing<int> ring(4);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(ring.try_push(i));
  EXPECT_FALSE(ring.try_push(99));
  EXPECT_EQ(ring.dropped(), 1u);
  for (int i = 0; i < 4; ++i) {
    ASSERT_NE(ring.front(), nullptr);
    EXPECT_EQ(*ring.front(), i);
    ring.pop();
  }
  EXPECT_EQ(ring.front(), nullptr);
}

TEST(SpscRing, DeliversEverythingInOrderAcrossThreads) {
  SpscRing<std::uint64_t> ring(64);
  constexpr std::uint64_t kN = 500000;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kN;) {
      if (ring.try_push(i)) ++i;
    }
  });
  std::uint64_t expected = 0;
  while (expected < kN) {
    if (const auto* v = ring.front()) {
      ASSERT_EQ(*v, expected);
      ring.pop();
      ++expected;
    }
  }
  producer.join();
  EXPECT_EQ(ring.pushed(), kN);
}

}  // namespace
}  // namespace facectl
