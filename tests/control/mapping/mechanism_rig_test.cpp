// The default rig's 3-strut mandible mechanism in the tick: the struts follow
// the face's jaw pose by inverse kinematics, move together (the pose their
// commands make never leaves the envelope, and no strut exceeds its own
// limits, even under bang-bang jaw commands), and rigs that get the mechanism
// wrong are refused naming where.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/run/offline_head.hpp"
#include "tests/support/temp_file.hpp"
#include "tests/support/text_files.hpp"

namespace facectl {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::string default_rig_text() {
  return testing::read_text(testing::source_path("config/rigs/default.yaml"));
}

LoadedConfig load_rig_text(const std::string& text, bool keep_problems = false) {
  testing::TempFile file(text);
  ConfigOverrides o;
  o.rig_path = file.path();
  o.keep_problems = keep_problems;
  return load_config(default_config_path(), o);
}

std::string load_error(const std::string& text) {
  try {
    load_rig_text(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

face::MandiblePose commanded_pose(OfflineHead& head, const face::MandiblePose& guess) {
  const MandibleMechanism& mech = *head.model().mapping.mechanism;
  MandibleStrokes s{};
  for (std::size_t i = 0; i < mech.struts(); ++i) {
    s[i] = head.controller().commands()[mech.strut[i].actuator];
  }
  const auto pose = forward(mech, s, guess);
  EXPECT_TRUE(pose.has_value());
  return pose.value_or(face::MandiblePose{});
}

TEST(MechanismRig, TheStrutsPutTheJawWhereTheFaceAsks) {
  OfflineHead head(load_config(default_config_path(), {}), 0, true);
  ASSERT_TRUE(head.model().mapping.mechanism.has_value());
  head.controller().request_enable();
  const FaceLayout& l = head.model().layout;
  auto face = head.model().neutral;
  const face::MandiblePose targets[] = {
      {12 * kDeg, 2 * kDeg, 3e-3}, {-3 * kDeg, 0, 0}, {16 * kDeg, -4.5 * kDeg, 7e-3}, {0, 0, 0}};
  for (const face::MandiblePose& t : targets) {
    face[l.jaw_pitch()] = t.pitch_rad;
    face[l.jaw_yaw()] = t.yaw_rad;
    face[l.jaw_protrusion()] = t.protrusion_m;
    head.send(face);
    head.run_for(1.5);
    ASSERT_EQ(head.controller().state(), SafetyState::kRunning);
    // What the tick decided (after the coupled yaw band), and where the struts put it.
    const auto& f = head.controller().face();
    const face::MandiblePose got = commanded_pose(head, {});
    EXPECT_NEAR(got.pitch_rad / kDeg, f[l.jaw_pitch()] / kDeg, 0.01);
    EXPECT_NEAR(got.yaw_rad / kDeg, f[l.jaw_yaw()] / kDeg, 0.01);
    EXPECT_NEAR(got.protrusion_m * 1e3, f[l.jaw_protrusion()] * 1e3, 0.01);
  }
}

TEST(MechanismRig, BangBangJawCommandsKeepTheStrutPoseInsideTheEnvelope) {
  OfflineHead head(load_config(default_config_path(), {}), 0, true);
  const ControllerModel& m = head.model();
  const MandibleMechanism& mech = *m.mapping.mechanism;
  head.controller().request_enable();
  std::mt19937_64 rng(3);
  auto face = m.neutral;
  const FaceLayout& l = m.layout;
  std::array<double, 3> prev{}, prev_v{};
  face::MandiblePose pose;
  double worst_envelope = 1.0, worst_velocity = 1.0, worst_acceleration = 1.0;
  const double dt = head.period();
  for (int t = 0; t < 30000; ++t) {
    if (t % (50 + static_cast<int>(rng() % 150)) == 0) {  // a new extreme every 50-200 ms
      face[l.jaw_pitch()] = rng() % 2 ? 18 * kDeg : -4 * kDeg;
      face[l.jaw_yaw()] = rng() % 2 ? 5 * kDeg : -5 * kDeg;
      face[l.jaw_protrusion()] = rng() % 2 ? 8e-3 : 0.0;
      head.send(face);
    }
    head.step(dt);
    if (head.controller().state() != SafetyState::kRunning) continue;
    pose = commanded_pose(head, pose);
    const MandibleEnvelope& e = m.envelope;
    worst_envelope =
        std::min({worst_envelope, pose.pitch_rad - e.pitch.min, e.pitch.max - pose.pitch_rad,
                  pose.yaw_rad - e.yaw.min, e.yaw.max - pose.yaw_rad,
                  pose.protrusion_m - e.protrusion.min, e.protrusion.max - pose.protrusion_m});
    for (std::size_t s = 0; s < mech.struts(); ++s) {
      const std::size_t i = mech.strut[s].actuator;
      const double x = head.controller().commands()[i];
      const double v = (x - prev[s]) / dt, a = (v - prev_v[s]) / dt;
      if (t > 2000) {
        worst_velocity =
            std::min(worst_velocity, 1.0 - std::fabs(v) / m.actuators[i].limits.max_velocity);
        worst_acceleration = std::min(worst_acceleration,
                                      1.0 - std::fabs(a) / m.actuators[i].limits.max_acceleration);
      }
      prev[s] = x;
      prev_v[s] = v;
    }
  }
  EXPECT_GE(worst_envelope, -1e-9);
  EXPECT_GE(worst_velocity, -1e-9);
  EXPECT_GE(worst_acceleration, -1e-9);
  // The test is not vacuous: the jaw reached the envelope's edges.
  EXPECT_LT(worst_envelope, 1e-4);
}

TEST(MechanismRig, StrutsRestingAtNoPoseOfTheJawAreAProblemAndEnableFaults) {
  // The digastric rests at 47 mm, its stroke at the mandible's rest 35 mm: that
  // is the jaw about 7 degrees closed, outside the envelope.
  std::string text = testing::replaced_once(default_rig_text(), "rest_mm: 35", "rest_mm: 47");
  text = testing::replaced_once(text, "mandible_mm: [0, -78, 38] }",
                                "mandible_mm: [0, -78, 38], stroke_at_rest_mm: 35 }");
  LoadedConfig cfg = load_rig_text(text, true);
  ASSERT_FALSE(cfg.built.problems.empty());
  EXPECT_NE(cfg.built.problems[0].find("struts' rest positions are no mandible pose"),
            std::string::npos)
      << cfg.built.problems[0];
  OfflineHead head(std::move(cfg), 0, true);
  head.controller().request_enable();
  head.run_for(0.1);
  EXPECT_EQ(head.controller().state(), SafetyState::kFault);
}

TEST(MechanismRig, ConfigMistakesAreNamed) {
  const std::string rig = default_rig_text();
  std::string e = load_error(
      testing::replaced_once(rig, "- { actuator: jaw_digastric,", "- { actuator: jaw_digastrik,"));
  EXPECT_NE(e.find("rig.mandible_mechanism.struts.actuator: expected the name of an actuator of "
                   "this rig, found 'jaw_digastrik'"),
            std::string::npos)
      << e;
  e = load_error(testing::replaced_once(
      rig, "      rest_mm: 35\n",
      "      rest_mm: 35\n      map: { terms: { jaw_pitch_deg: -1.67 } }\n"));
  EXPECT_NE(e.find("expected no `map` for a strut of the mandible mechanism"), std::string::npos)
      << e;
  e = load_error(testing::replaced_once(rig, "      pitch: { max_velocity_deg_s: 150,",
                                        "      pitch: { max_velocity_deg_s: -150,"));
  EXPECT_NE(e.find("rig.mandible_mechanism.limits.pitch.max_velocity_deg_s"), std::string::npos)
      << e;
  e = load_error(testing::replaced_once(rig, "    dofs: [pitch, yaw, protrusion]",
                                        "    dofs: [pitch, yaw, yaw]"));
  EXPECT_NE(e.find("each degree of freedom once"), std::string::npos) << e;
  // Too slow struts for the jaw's rates: a problem the run refuses, with numbers.
  LoadedConfig slow = load_rig_text(
      testing::replaced_once(rig, "max_velocity_mm_s: 350", "max_velocity_mm_s: 100"), true);
  ASSERT_EQ(slow.built.problems.size(), 1u);
  EXPECT_NE(slow.built.problems[0].find("can ask strut 'jaw_digastric' for"), std::string::npos)
      << slow.built.problems[0];
}

}  // namespace
}  // namespace facectl
