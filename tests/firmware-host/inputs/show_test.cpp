#include "firmware-host/inputs/show.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "firmware-host/config/loaded_config.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

using testing::TempFile;

class ShowTest : public ::testing::Test {
 protected:
  LoadedConfig cfg_ = load_config(default_config_path());
  Show load(const std::string& text) {
    TempFile f(text);
    return Show::load(f.path(), cfg_.head.layout, cfg_.head.neutral, cfg_.expressions);
  }
  std::string error_of(const std::string& text) {
    TempFile f(text);
    try {
      Show::load(f.path(), cfg_.head.layout, cfg_.head.neutral, cfg_.expressions);
    } catch (const ConfigError& e) {
      std::string msg = e.what();
      // Replace the temp path so tests can compare positions.
      return msg.replace(0, f.path().size(), "SHOW");
    }
    return "no error";
  }
};

TEST_F(ShowTest, InterpolatesWithTheEasingOfTheTargetKeyframe) {
  const Show s = load(
      "show:\n  name: t\n  keyframes:\n"
      "    - { t: 0, mandible: { pitch_deg: 0 } }\n"
      "    - { t: 2, mandible: { pitch_deg: 10 }, ease: linear }\n"
      "    - { t: 4, mandible: { pitch_deg: 0 }, ease: step }\n");
  std::array<double, kMaxFaceSignals> out{};
  const std::size_t pitch = cfg_.head.layout.jaw_pitch();
  const double deg = std::numbers::pi / 180.0;
  s.evaluate(1.0, out);
  EXPECT_NEAR(out[pitch], 5 * deg, 1e-12);
  s.evaluate(3.0, out);
  EXPECT_NEAR(out[pitch], 10 * deg, 1e-12);  // step holds until its keyframe
  s.evaluate(4.5, out);
  EXPECT_NEAR(out[pitch], 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.duration(), 4.0);
}

TEST_F(ShowTest, BlendsAnExpressionByWeightAndAppliesOverrides) {
  const Show s = load(
      "show:\n  name: t\n  keyframes:\n"
      "    - { t: 0, expression: joy, weight: 0.5, muscles: { zygomaticus_major_r: 0.1 } }\n");
  std::array<double, kMaxFaceSignals> out{};
  s.evaluate(0.0, out);
  const std::size_t zyg = *cfg_.head.layout.find("zygomaticus_major_l");
  const FacePose& joy = *cfg_.expressions.find("joy");
  ASSERT_TRUE(joy.set[zyg]);
  EXPECT_NEAR(out[zyg], 0.5 * joy.values[zyg], 1e-12);  // neutral is 0
  EXPECT_NEAR(out[*cfg_.head.layout.find("zygomaticus_major_r")], 0.1, 1e-12);
}

TEST_F(ShowTest, BadShowsNameTheirPositionKeyAndWhatWasWrong) {
  EXPECT_EQ(error_of("show:\n  name: t\n  keyframes:\n    - { t: 1 }\n    - { t: 0.5 }\n"),
            "SHOW:5:12: show.keyframes[1].t: expected a time after the previous keyframe's "
            "1.000000 s, found '0.5'");
  EXPECT_EQ(error_of("show:\n  name: t\n  keyframes:\n    - { t: 0, expression: glee }\n"),
            "SHOW:4:27: show.keyframes[0].expression: expected an expression of the library, "
            "found 'glee'");
  EXPECT_EQ(error_of("show:\n  name: t\n  keyframes:\n    - { t: 0, muscles: { zygo: 1 } }\n"),
            "SHOW:4:32: show.keyframes[0].muscles.zygo: expected a muscle of this head, found "
            "unknown muscle 'zygo'");
  EXPECT_EQ(error_of("show:\n  name: t\n  keyframes:\n    - { t: 0, ease: bouncy }\n"),
            "SHOW:4:21: show.keyframes[0].ease: expected one of: linear, ease_in, ease_out, "
            "ease_in_out, step, found 'bouncy'");
  EXPECT_EQ(
      error_of(
          "show:\n  name: t\n  keyframes: [ { t: 0, muscles: { zygomaticus_major_l: 1.5 } } ]\n"),
      "SHOW:3:56: show.keyframes[0].muscles.zygomaticus_major_l: expected a value of "
      "zygomaticus_major_l in [0.000000, 1.000000], found '1.5'");
  // One number must not buy a run of 30 years (issue 21).
  EXPECT_EQ(error_of("show:\n  name: t\n  keyframes:\n    - { t: 0 }\n    - { t: 1e9 }\n"),
            "SHOW:5:12: show.keyframes[1].t: expected a number in [0, 86400], found '1e9'");
  EXPECT_EQ(error_of("show:\n  name: t\n  keyframes:\n    - { t: 0 }\n    - { t: 86400 }\n"),
            "no error");
}

}  // namespace
}  // namespace facectl
