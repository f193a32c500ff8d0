#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "control/face/mandible.hpp"
#include "default_fap_head.hpp"
#include "facectl/face/head_spec.hpp"
#include "firmware-host/fap/fap_show.hpp"
#include "tests/support/jaw_geometry.hpp"

namespace facectl {
namespace testing {

std::string fap_frame_text(long number, const std::vector<std::pair<int, std::string>>& values) {
  std::string mask(2 * kFapCount - 1, ' ');
  for (int i = 0; i < kFapCount; ++i) mask[static_cast<std::size_t>(2 * i)] = '0';
  std::string line = std::to_string(number);
  for (const auto& [fap, text] : values) {
    mask[static_cast<std::size_t>(2 * (fap - 1))] = '1';
    line += " " + text;
  }
  return mask + "\n" + line + "\n";
}

}  // namespace testing

namespace {

using testing::default_fap_head;
using testing::fap_frame_text;
constexpr double kDeg = std::numbers::pi / 180.0;

// Values must be given in ascending FAP order (the file format's order).
FapSequence sequence(const std::vector<std::vector<std::pair<int, std::string>>>& frames) {
  std::string text = "2.1 test 25 " + std::to_string(frames.size()) + "\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    text += fap_frame_text(static_cast<long>(k), frames[k]);
  }
  return parse_fap_text(text, "test");
}

FeaturePoints default_points() {
  return FeaturePoints::load(
      face::load_head_spec(std::string(FACECTL_SOURCE_DIR) + "/config/heads/default"));
}

double signal(const std::array<double, kMaxFaceSignals>& pose, std::string_view name) {
  return pose[*default_fap_head().head.layout.find(name)];
}

TEST(Fapu, DefaultHeadWithinHumanRanges) {
  const Fapu f = compute_fapu(default_points());
  // Adult faces (and the MediaPipe canonical face the head is built on), mm.
  EXPECT_GT(f.es0 * 1e3, 55.0);
  EXPECT_LT(f.es0 * 1e3, 75.0);
  EXPECT_GT(f.ens0 * 1e3, 30.0);
  EXPECT_LT(f.ens0 * 1e3, 55.0);
  EXPECT_GT(f.mns0 * 1e3, 12.0);
  EXPECT_LT(f.mns0 * 1e3, 30.0);
  EXPECT_GT(f.mw0 * 1e3, 40.0);
  EXPECT_LT(f.mw0 * 1e3, 60.0);
  EXPECT_GT(f.irisd0 * 1e3, 4.0);
  EXPECT_LT(f.irisd0 * 1e3, 14.0);
  EXPECT_DOUBLE_EQ(f.unit(FapUnit::kMNS), f.mns0 / 1024.0);
  EXPECT_DOUBLE_EQ(f.unit(FapUnit::kAU), 1e-5);
}

TEST(Fapu, MissingFeaturePointIsNamed) {
  FeaturePoints fp;
  fp.set("fdp_3_5", {0.03, 0.02, 0.04});
  try {
    (void)compute_fapu(fp);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("fdp_9_"), std::string::npos) << e.what();
  }
}

TEST(FapMapping, OpenJawSequenceReachesTheGeometricPitch) {
  const FeaturePoints fp = default_points();
  const double mns0 = testing::mns0(fp);
  const std::vector<double> opens = {0, 64, 128, 256, 384, 512, 600, 300, 0};
  std::vector<std::vector<std::pair<int, std::string>>> frames;
  for (double v : opens) frames.push_back({{3, std::to_string(static_cast<int>(v))}});
  const FapShow show = FapShow::build(sequence(frames), default_fap_head().mapping);
  EXPECT_TRUE(show.clamps().empty());
  std::array<double, kMaxFaceSignals> pose{};
  for (std::size_t k = 0; k < opens.size(); ++k) {
    show.evaluate(static_cast<double>(k) / 25.0, pose);
    const double want = testing::expected_jaw_pitch(fp, opens[k] * mns0 / 1024.0);
    EXPECT_NEAR(signal(pose, "jaw_pitch") / kDeg, want / kDeg, 0.1) << "open_jaw " << opens[k];
  }
  // A real opening: half an MNS0 opens the jaw by several degrees.
  show.evaluate(5.0 / 25.0, pose);
  EXPECT_GT(signal(pose, "jaw_pitch") / kDeg, 5.0);
  // Between frames the pose is interpolated linearly.
  std::array<double, kMaxFaceSignals> a{}, b{}, mid{};
  show.evaluate(2.0 / 25.0, a);
  show.evaluate(3.0 / 25.0, b);
  show.evaluate(2.5 / 25.0, mid);
  EXPECT_NEAR(signal(mid, "jaw_pitch"), 0.5 * (signal(a, "jaw_pitch") + signal(b, "jaw_pitch")),
              1e-12);
}

TEST(FapMapping, BeyondTheEnvelopeIsClampedAndReported) {
  const FapShow show =
      FapShow::build(sequence({{{3, "100"}}, {{3, "4000"}, {12, "5000"}}, {{3, "-50"}}}),
                     default_fap_head().mapping);
  std::array<double, kMaxFaceSignals> pose{};
  show.evaluate(1.0 / 25.0, pose);
  EXPECT_NEAR(signal(pose, "jaw_pitch") / kDeg, 18.0, 1e-9);
  EXPECT_DOUBLE_EQ(signal(pose, "zygomaticus_major_l"), 1.0);
  bool pitch = false, muscle = false, negative = false;
  for (const FapClamp& c : show.clamps()) {
    if (c.frame == 1 && c.fap == 3 && c.signal == "jaw_pitch") {
      pitch = true;
      EXPECT_GT(c.requested / kDeg, 18.0);
      EXPECT_NEAR(c.applied / kDeg, 18.0, 1e-9);
      EXPECT_NE(describe(c).find("frame 1, FAP 3 open_jaw: jaw_pitch"), std::string::npos)
          << describe(c);
    }
    if (c.frame == 1 && c.fap == 12 && c.signal == "zygomaticus_major_l") {
      muscle = true;
      EXPECT_GT(c.requested, 1.0);
    }
    if (c.frame == 2 && c.fap == 3 && c.signal == "open_jaw") negative = true;
  }
  EXPECT_TRUE(pitch);
  EXPECT_TRUE(muscle);
  EXPECT_TRUE(negative) << "a negative unidirectional open_jaw is reported";
  EXPECT_FALSE(show.report().empty());
  // Frame 0 is inside the envelope: nothing reported for it.
  for (const FapClamp& c : show.clamps()) EXPECT_NE(c.frame, 0);
}

// A file that clamps in every frame must not give a report as long as the
// file (it goes into summary.json, summary.txt and index.html).
TEST(FapMapping, ClampsBeyondTheFirstHundredAreCountedNotListed) {
  const std::vector<std::vector<std::pair<int, std::string>>> frames(300, {{3, "4000"}});
  const FapShow show = FapShow::build(sequence(frames), default_fap_head().mapping);
  ASSERT_EQ(show.clamps().size(), FapShow::kMaxClampNotes);
  EXPECT_EQ(show.clamps().back().frame, 99);
  EXPECT_EQ(show.clamps_left_out(), 200u);
  const std::vector<std::string> report = show.report();
  ASSERT_EQ(report.size(), 101u);
  EXPECT_EQ(report.back(), "clamped: 200 more values after frame 99 (the first 100 are listed)");
}

TEST(FapMapping, UnsupportedFapsAreListedAsIgnored) {
  const FapShow show =
      FapShow::build(sequence({{{3, "10"}, {43, "100"}, {65, "5"}}}), default_fap_head().mapping);
  EXPECT_EQ(show.ignored_faps(), (std::vector<int>{43, 65}));
  const auto lines = show.report();
  ASSERT_FALSE(lines.empty());
  EXPECT_NE(lines.back().find("43 shift_tongue_tip, 65 raise_l_ear"), std::string::npos)
      << lines.back();
}

TEST(FapMapping, MusclesFollowTheFapsDirection) {
  const FapMapping& m = default_fap_head().mapping;
  std::array<double, kMaxFaceSignals> pose{};
  FapState s;
  s.values[11] = 150;  // raise_l_cornerlip up
  m.map(s, 0, pose, nullptr);
  EXPECT_GT(signal(pose, "zygomaticus_major_l"), 0.05);
  EXPECT_EQ(signal(pose, "depressor_anguli_oris_l"), 0.0);
  EXPECT_EQ(signal(pose, "zygomaticus_major_r"), 0.0);
  s.values[11] = -150;  // down
  m.map(s, 0, pose, nullptr);
  EXPECT_GT(signal(pose, "depressor_anguli_oris_l"), 0.05);
  EXPECT_EQ(signal(pose, "zygomaticus_major_l"), 0.0);
  // More FAP, more contraction.
  s = {};
  s.values[30] = 100;  // raise_l_i_eyebrow
  m.map(s, 0, pose, nullptr);
  const double small = signal(pose, "frontalis_inner_l");
  s.values[30] = 300;
  m.map(s, 0, pose, nullptr);
  EXPECT_GT(small, 0.0);
  EXPECT_GT(signal(pose, "frontalis_inner_l"), small);
}

TEST(FapMapping, EyelidsEyesHeadAndJawShift) {
  const FapMapping& m = default_fap_head().mapping;
  std::array<double, kMaxFaceSignals> pose{};
  FapState s;
  s.values[18] = 768;    // close_t_l_eyelid
  s.values[20] = 256;    // close_b_l_eyelid
  s.values[22] = 10000;  // yaw_l_eyeball, 0.1 rad to the left
  s.values[24] = 10000;  // pitch_l_eyeball, 0.1 rad down
  s.values[47] = 20000;  // head_pitch, 0.2 rad down
  s.values[14] = 50;     // shift_jaw to the right (2.4 mm)
  m.map(s, 0, pose, nullptr);
  EXPECT_NEAR(signal(pose, "eyelid_closure_l"), 1.0, 1e-12);
  EXPECT_EQ(signal(pose, "eyelid_closure_r"), 0.0);
  EXPECT_NEAR(signal(pose, "eye_yaw_l"), 0.1, 1e-12);
  EXPECT_NEAR(signal(pose, "eye_pitch_l"), -0.1, 1e-12);
  EXPECT_NEAR(signal(pose, "neck_tilt"), -0.2, 1e-12);
  EXPECT_LT(signal(pose, "jaw_yaw"), 0.0) << "chin to the right is negative yaw";
  EXPECT_GT(signal(pose, "jaw_yaw"), -5.0 * kDeg);
}

TEST(FapMapping, VisemesAndExpressionsComeFromTheirTables) {
  const testing::DefaultFapHead& h = default_fap_head();
  std::array<double, kMaxFaceSignals> pose{};
  FapState s;
  s.expression = {1, 63, 0, 0, 0, 0};  // joy at full intensity
  h.mapping.map(s, 0, pose, nullptr);
  const FacePose& joy = *h.expressions.find("joy");
  const std::size_t zyg = *h.head.layout.find("zygomaticus_major_l");
  EXPECT_NEAR(pose[zyg], joy.values[zyg], 1e-12);
  s = {};
  s.viseme = {10, 0, 0, 0};  // A:, fully
  h.mapping.map(s, 0, pose, nullptr);
  EXPECT_NEAR(signal(pose, "jaw_pitch") / kDeg, 14.0, 1e-9);
  s.viseme = {10, 1, 63, 0};  // blended all the way to p/b/m
  h.mapping.map(s, 0, pose, nullptr);
  EXPECT_NEAR(signal(pose, "jaw_pitch") / kDeg, 0.0, 1e-9);
  EXPECT_NEAR(signal(pose, "orbicularis_oris"), 0.35, 1e-12);
}

TEST(FapMapping, UntransmittedFapsHoldTheirLastValue) {
  const FapShow show = FapShow::build(sequence({{{3, "512"}, {12, "100"}}, {{12, "0"}}}),
                                      default_fap_head().mapping);
  std::array<double, kMaxFaceSignals> a{}, b{};
  show.evaluate(0.0, a);
  show.evaluate(1.0 / 25.0, b);
  EXPECT_GT(signal(a, "jaw_pitch"), 0.0);
  EXPECT_DOUBLE_EQ(signal(b, "jaw_pitch"), signal(a, "jaw_pitch"));
  EXPECT_EQ(signal(b, "zygomaticus_major_l"), 0.0);
}

TEST(FapMapping, TheDemoPlaysInsideTheEnvelope) {
  const FapSequence seq = load_fap_file(std::string(FACECTL_SOURCE_DIR) + "/config/fap/demo.fap");
  const FapShow show = FapShow::build(seq, default_fap_head().mapping);
  for (const auto& line : show.report()) ADD_FAILURE() << line;
  std::array<double, kMaxFaceSignals> pose{};
  show.evaluate(0.6, pose);  // the jaw at its widest
  EXPECT_GT(signal(pose, "jaw_pitch") / kDeg, 5.0);
  show.evaluate(1.8, pose);  // the smile
  EXPECT_GT(signal(pose, "zygomaticus_major_l"), 0.1);
}

}  // namespace
}  // namespace facectl

namespace facectl {
namespace {

// Every FAP the mapping supports has a documented route; printed for docs/FAP.md.
TEST(FapMapping, EverySupportedFapHasARoute) {
  const FapMapping& m = testing::default_fap_head().mapping;
  const auto routes = m.describe_routes();
  for (const FapRouteInfo& r : routes) {
    std::cout << r.fap << " | " << fap_info(r.fap).name << " | " << r.target << " | " << r.gain
              << "\n";
    EXPECT_TRUE(m.supported()[static_cast<std::size_t>(r.fap - 1)]);
  }
  EXPECT_EQ(routes.size() + 13, m.supported().count())
      << "routes cover the jaw and muscle FAPs; 13 more (1, 2, 19-26, 48-50) go straight to "
         "signals or tables";
}

}  // namespace
}  // namespace facectl
