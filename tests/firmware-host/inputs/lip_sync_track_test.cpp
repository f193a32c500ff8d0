// Lip sync as poses: a pose where one viseme has all the weight is exactly
// that viseme's mouth pose (config/fap/visemes.yaml), and the face is at rest
// away from speech.
#include "firmware-host/inputs/lip_sync_track.hpp"

#include <gtest/gtest.h>

#include "default_retarget.hpp"
#include "firmware-host/inputs/phoneme_track_builder.hpp"

namespace facectl {
namespace {

TEST(LipSyncTrack, AClosureIsTheVisemesPoseExactlyAndRestIsNeutral) {
  const HeadConfig& head = testing::default_head_config();
  const VisemeTable visemes =
      VisemeTable::load(std::string(FACECTL_SOURCE_DIR) + "/config/fap/visemes.yaml", head.layout);
  PhonemeTrack phones;
  phones.segments.push_back({1.0, 1.5, "M", kVisemePBM, 1});
  phones.duration_s = 3.0;
  const PoseTrack track =
      lip_sync_pose_track(VisemeTimeline::build(phones, {}), visemes, head.layout, head.neutral);
  std::array<double, kMaxFaceSignals> pose{};
  track.evaluate(1.25, pose);
  const FacePose& closed = visemes.pose(kVisemePBM);
  int set = 0;
  for (std::size_t i = 0; i < head.layout.size(); ++i) {
    const double expected = closed.set.test(i) ? closed.values[i] : head.neutral[i];
    EXPECT_NEAR(pose[i], expected, 1e-12) << head.layout.signal(i).name;
    set += closed.set.test(i);
  }
  EXPECT_GE(set, 3);  // orbicularis oris, both mentalis, the jaw
  track.evaluate(2.9, pose);
  for (std::size_t i = 0; i < head.layout.size(); ++i) {
    EXPECT_NEAR(pose[i], head.neutral[i], 1e-3) << head.layout.signal(i).name;
  }
}

TEST(LipSyncTrack, AZeroLengthClosureIsSkippedNotFlashed) {
  PhonemeTrackBuilder b("f");
  b.add(0.4, 0.5, "AA1", kVisemeA, 1);
  b.add(0.5, 0.5, "M", kVisemePBM, 2);
  b.add(0.5, 0.6, "AA1", kVisemeA, 3);
  const PhonemeTrack t = b.finish(0.6);
  ASSERT_EQ(t.segments.size(), 2u);
  EXPECT_EQ(t.notes.back(), "skipped 1 segments shorter than 0.1 ms");
}

TEST(LipSyncTrack, UnknownLabelsAreNotedOnceEachAndThenCounted) {
  PhonemeTrackBuilder b("f");
  for (int i = 0; i < 25; ++i) {
    b.add(i * 0.1, i * 0.1 + 0.05, "zz" + std::to_string(i), -1, i + 1);
    b.add(i * 0.1 + 0.05, i * 0.1 + 0.1, "zz0", -1, i + 1);  // a repeat: no new note
  }
  const PhonemeTrack t = b.finish(0);
  ASSERT_EQ(t.notes.size(), 21u);
  EXPECT_EQ(t.notes.back(), "5 more unknown phones read as silence");
}

}  // namespace
}  // namespace facectl
