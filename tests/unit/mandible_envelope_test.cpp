#include "control/mandible_envelope.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "firmware-host/config_node.hpp"
#include "firmware-host/head_config.hpp"
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
  EXPECT_DOUBLE_EQ(spec.envelope.pitch.max, 12 * kDeg);
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
    EXPECT_NE(msg.find(f.path() + ":4:3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("widen_override"), std::string::npos) << msg;
  }
}

TEST(EnvelopeConfig, WideningWithTheOverrideIsAccepted) {
  testing::TempFile f(
      "mandible_envelope: { pitch_deg: { min: -4, max: 22 }, widen_override: true }\n");
  const ConfigNode root = ConfigNode::load_file(f.path(), "");
  const EnvelopeSpec spec = parse_envelope(root["mandible_envelope"]);
  EXPECT_TRUE(spec.widen_override);
  EXPECT_DOUBLE_EQ(spec.envelope.pitch.max, 22 * kDeg);
}

}  // namespace
}  // namespace facectl
