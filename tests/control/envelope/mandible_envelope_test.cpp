#include "control/envelope/mandible_envelope.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "control/envelope/face_envelope.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/model/model_builder.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(MandibleEnvelope, DesignDefaultIsTheSafetyEnvelope) {
  const MandibleEnvelope e = MandibleEnvelope::design_default();
  EXPECT_DOUBLE_EQ(e.pitch.min, -4 * kDeg);
  EXPECT_DOUBLE_EQ(e.pitch.max, 18 * kDeg);
  EXPECT_DOUBLE_EQ(e.yaw.min, -5 * kDeg);
  EXPECT_DOUBLE_EQ(e.yaw.max, 5 * kDeg);
  EXPECT_DOUBLE_EQ(e.protrusion.min, 0.0);
  EXPECT_DOUBLE_EQ(e.protrusion.max, 8e-3);
}

TEST(FaceEnvelope, ClampsTheMandibleAndFlagsWhichLimitFired) {
  const FaceLayout layout({"m_l"});
  std::array<Range, kMaxFaceSignals> admissible{};
  for (auto& r : admissible) r = {-10, 10};
  FaceEnvelope env(layout, MandibleEnvelope::design_default(), admissible);
  std::array<double, kMaxFaceSignals> v{};
  v[layout.jaw_pitch()] = 30 * kDeg;
  v[layout.jaw_yaw()] = -9 * kDeg;
  v[layout.jaw_protrusion()] = 0.004;
  const std::uint8_t flags = env.apply(v);
  EXPECT_DOUBLE_EQ(v[layout.jaw_pitch()], 18 * kDeg);
  EXPECT_DOUBLE_EQ(v[layout.jaw_yaw()], -5 * kDeg);
  EXPECT_DOUBLE_EQ(v[layout.jaw_protrusion()], 0.004);
  EXPECT_EQ(flags, FaceEnvelope::kPitchClamped | FaceEnvelope::kYawClamped);
  EXPECT_EQ(env.clamp_count(), 1u);
}

TEST(EnvelopeConfig, NarrowingIsAcceptedSilently) {
  testing::TempFile f("mandible_envelope: { pitch_deg: { min: -2, max: 12 } }\n");
  const ConfigNode root = ConfigNode::load_file(f.path(), "");
  const EnvelopeSpec spec = parse_envelope(root["mandible_envelope"]);
  ASSERT_TRUE(spec.pitch.has_value());
  EXPECT_DOUBLE_EQ(spec.pitch->max, 12 * kDeg);
  EXPECT_FALSE(spec.yaw.has_value());
  EXPECT_FALSE(spec.widen_override);
}

TEST(EnvelopeConfig, WideningWithoutTheOverrideIsRefusedWithItsPosition) {
  testing::TempFile f("head:\n  x: 1\nmandible_envelope:\n  yaw_deg: { min: -8, max: 8 }\n");
  const ConfigNode root = ConfigNode::load_file(f.path(), "");
  try {
    parse_envelope(root["mandible_envelope"]);
    FAIL() << "a widened envelope was accepted";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg, f.path() +
                       ":4:12: mandible_envelope.yaw_deg: expected a range inside the design "
                       "envelope -5..5 deg (widening needs `widen_override: true`), found "
                       "[-8.000000, 8.000000]");
  }
}

TEST(EnvelopeConfig, WideningWithTheOverrideIsAccepted) {
  testing::TempFile f(
      "mandible_envelope: { pitch_deg: { min: -4, max: 22 }, widen_override: true }\n");
  const ConfigNode root = ConfigNode::load_file(f.path(), "");
  const EnvelopeSpec spec = parse_envelope(root["mandible_envelope"]);
  EXPECT_TRUE(spec.widen_override);
  EXPECT_DOUBLE_EQ(spec.pitch->max, 22 * kDeg);
}

// Head and rig envelopes combine axis by axis.
class EnvelopeMerge : public ::testing::Test {
 protected:
  LoadedConfig cfg_ = load_config(default_config_path());
  EnvelopeSpec spec(std::optional<Range> pitch, bool widen) {
    EnvelopeSpec s;
    s.pitch = pitch;
    s.widen_override = widen;
    s.where = "here:1:1";
    return s;
  }
};

TEST_F(EnvelopeMerge, ARigOverrideBlockThatStatesNoAxisKeepsTheHeadsNarrowing) {
  cfg_.head.envelope = spec(Range{0, 10 * kDeg}, false);
  cfg_.rig.envelope = spec(std::nullopt, true);
  const BuiltModel b = build_model(cfg_.head, cfg_.rig, cfg_.runtime);
  EXPECT_DOUBLE_EQ(b.model.envelope.pitch.max, 10 * kDeg);
  EXPECT_FALSE(b.model.envelope_widened);
  EXPECT_TRUE(b.warnings.empty());
}

TEST_F(EnvelopeMerge, ARigNarrowsTheHeadAndAnOverrideWidensLoudly) {
  cfg_.head.envelope = spec(Range{-2 * kDeg, 10 * kDeg}, false);
  cfg_.rig.envelope = spec(Range{0, 12 * kDeg}, false);
  BuiltModel b = build_model(cfg_.head, cfg_.rig, cfg_.runtime);
  EXPECT_DOUBLE_EQ(b.model.envelope.pitch.min, 0.0);
  EXPECT_DOUBLE_EQ(b.model.envelope.pitch.max, 10 * kDeg);

  cfg_.rig.envelope = spec(Range{-4 * kDeg, 20 * kDeg}, true);
  b = build_model(cfg_.head, cfg_.rig, cfg_.runtime);
  EXPECT_DOUBLE_EQ(b.model.envelope.pitch.max, 20 * kDeg);
  EXPECT_TRUE(b.model.envelope_widened);
  ASSERT_EQ(b.warnings.size(), 2u);
  EXPECT_NE(b.warnings[0].find("WIDENED beyond the design default by here:1:1"), std::string::npos);
  EXPECT_NE(b.warnings[1].find("the rig WIDENS the head's mandible envelope"), std::string::npos);
  // Beyond the joint limits (18 deg): a problem, which `facectl run` refuses.
  ASSERT_EQ(b.problems.size(), 1u);
  EXPECT_NE(b.problems[0].find("here:1:1: mandible_envelope.pitch_deg: -4..20 deg, beyond the "
                               "mandible's joint limits -4..18 deg"),
            std::string::npos)
      << b.problems[0];

  // Up to them, the override undoes the head's narrowing without a problem.
  cfg_.rig.envelope = spec(Range{-4 * kDeg, 18 * kDeg}, true);
  b = build_model(cfg_.head, cfg_.rig, cfg_.runtime);
  EXPECT_DOUBLE_EQ(b.model.envelope.pitch.max, 18 * kDeg);
  EXPECT_TRUE(b.problems.empty());
}

}  // namespace
}  // namespace facectl
