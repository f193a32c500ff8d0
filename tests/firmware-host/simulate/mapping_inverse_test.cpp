#include "firmware-host/simulate/mapping_inverse.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"

namespace facectl {
namespace {

const LoadedConfig& rig(const std::string& name) {
  static std::map<std::string, std::unique_ptr<LoadedConfig>> cache;
  auto& c = cache[name];
  if (!c) {
    ConfigOverrides o;
    // hobby_terms: the hobby rig with linear terms only (tests/data/rigs).
    o.rig_path = std::string(FACECTL_SOURCE_DIR) +
                 (name == "hobby_terms" ? "/tests/data/rigs/" : "/config/rigs/") + name + ".yaml";
    c = std::make_unique<LoadedConfig>(load_config(default_config_path(), o));
  }
  return *c;
}

using Face = std::array<double, kMaxFaceSignals>;
using Positions = std::array<double, kMaxActuators>;

// A face drawn uniformly from the inverse's box (muscles, envelope, rigid ranges).
Face random_face(const MappingInverse& inv, std::mt19937& rng) {
  Face f = inv.neutral;
  for (std::size_t s = 0; s < inv.signals; ++s) {
    f[s] = std::uniform_real_distribution<double>(inv.lower[s], inv.upper[s])(rng);
  }
  return f;
}

// The rig's forward map. Where the mechanism cannot reach the jaw pose, the
// face takes the pose it does reach, so that the face and positions agree.
Positions map(const ControllerModel& m, Face& face) {
  MappingWorkspace w = make_mapping_workspace(m.mapping);
  Positions p{};
  map_to_actuators(m.mapping, w, face, p);
  if (m.mapping.mechanism && w.mechanism.clamped) {
    face[m.mapping.jaw_pitch] = w.mechanism.achieved.pitch_rad;
    face[m.mapping.jaw_yaw] = w.mechanism.achieved.yaw_rad;
    face[m.mapping.jaw_protrusion] = w.mechanism.achieved.protrusion_m;
    map_to_actuators(m.mapping, w, face, p);
  }
  return p;
}

double span(const ActuatorModel& a) {
  return a.limits.position_max - a.limits.position_min;
}

class MappingInverseTest : public ::testing::TestWithParam<std::string> {};

// face → map → positions → inverse → map reproduces the positions.
TEST_P(MappingInverseTest, ReproducesThePositionsOfRandomFaces) {
  const ControllerModel& m = rig(GetParam()).built.model;
  const MappingInverse inv = make_mapping_inverse(m);
  MappingInverseWorkspace w = make_mapping_inverse_workspace(inv);
  std::mt19937 rng(6);
  double worst = 0.0;
  for (int sample = 0; sample < 100; ++sample) {
    Face face = random_face(inv, rng);
    const Positions p = map(m, face);
    Face back{};
    const MappingInverseResult r = invert_mapping(inv, w, p, back);
    ASSERT_TRUE(r.mandible_solved);
    for (std::size_t s = 0; s < inv.signals; ++s) {
      ASSERT_GE(back[s], inv.lower[s]) << m.layout.signal(s).name;
      ASSERT_LE(back[s], inv.upper[s]) << m.layout.signal(s).name;
    }
    const Positions again = map(m, back);
    for (std::size_t a = 0; a < m.actuators.size(); ++a) {
      const double error = std::fabs(again[a] - p[a]) / span(m.actuators[a]);
      worst = std::max(worst, error);
      // Below a servo's resolution (one step of a 4096-step turn is 2.4e-4 of a 360°
      // range). With eight servos following brow, cheek and lip points, a single descent
      // from neutral stopped in a local minimum in 5 of these 100 faces (up to 8% of a
      // range); the second start from the box's middle brought the worst to 1e-5. With
      // the corner-down servos following the corners too (each corner read by two
      // servos), sample 57 stays at 1.9e-4 for the left pair and sample 7 at 9.1e-5 for
      // the right after both starts (100 iterations instead of 50 give the same); every
      // other face within 1e-5.
      EXPECT_LT(error, 2.4e-4) << "sample " << sample << ", " << m.actuators[a].name;
    }
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
  std::printf("worst position error: %.3g of the actuator range\n", worst);
}

// Signals one actuator alone measures come back exactly; the jaw comes back
// through the mechanism's forward kinematics or the jaw linkage.
TEST_P(MappingInverseTest, RecoversFullyObservedSignals) {
  const ControllerModel& m = rig(GetParam()).built.model;
  const MappingInverse inv = make_mapping_inverse(m);
  MappingInverseWorkspace w = make_mapping_inverse_workspace(inv);
  const std::vector<std::string> names =
      GetParam() == "default"
          ? std::vector<std::string>{"neck_pan",  "neck_tilt",     "neck_roll",   "eye_yaw_l",
                                     "eye_yaw_r", "eye_pitch_l",   "eye_pitch_r", "jaw_pitch",
                                     "jaw_yaw",   "jaw_protrusion"}
          : std::vector<std::string>{"neck_pan", "jaw_pitch", "eyelid_closure_l",
                                     "eyelid_closure_r"};
  std::mt19937 rng(7);
  for (int sample = 0; sample < 50; ++sample) {
    Face face = random_face(inv, rng);
    const Positions p = map(m, face);
    Face back{};
    invert_mapping(inv, w, p, back);
    for (const std::string& name : names) {
      const std::size_t s = *m.layout.find(name);
      EXPECT_NEAR(back[s], face[s], 1e-6 * inv.span[s]) << name << ", sample " << sample;
    }
  }
}

// What no actuator observes stays neutral, and really is unobserved: moving it
// moves no actuator.
TEST_P(MappingInverseTest, UnobservedSignalsStayNeutral) {
  const ControllerModel& m = rig(GetParam()).built.model;
  const MappingInverse inv = make_mapping_inverse(m);
  MappingInverseWorkspace w = make_mapping_inverse_workspace(inv);
  std::mt19937 rng(8);
  const Face face = random_face(inv, rng);
  Face mapped = face;
  const Positions p = map(m, mapped);
  Face back{};
  invert_mapping(inv, w, p, back);
  int unobserved = 0;
  for (std::size_t s = 0; s < inv.signals; ++s) {
    const bool jaw =
        s == m.mapping.jaw_pitch || s == m.mapping.jaw_yaw || s == m.mapping.jaw_protrusion;
    if (inv.observed[s] || (jaw && m.mapping.mechanism)) continue;
    ++unobserved;
    EXPECT_EQ(back[s], inv.neutral[s]) << m.layout.signal(s).name;
    Face moved = mapped;
    moved[s] = inv.upper[s] == moved[s] ? inv.lower[s] : inv.upper[s];
    const Positions q = map(m, moved);
    for (std::size_t a = 0; a < m.actuators.size(); ++a) {
      EXPECT_EQ(q[a], p[a]) << m.layout.signal(s).name << " moves " << m.actuators[a].name;
    }
  }
  if (GetParam() == "hobby") {  // its mouth corner servo follows the corner, which the
    EXPECT_TRUE(inv.observed[*m.layout.find("risorius_l")]);  // risorius moves
  }
  if (GetParam() == "hobby_terms") {
    EXPECT_FALSE(inv.observed[*m.layout.find("risorius_l")]);
    EXPECT_FALSE(inv.observed[*m.layout.find("jaw_yaw")]);
    EXPECT_GT(unobserved, 10);
  }
}

// Two signals through one actuator (the hobby rig's eyes_pan turns both eyes):
// the face nearest neutral that makes the same position, both eyes alike.
TEST(MappingInverse, SharedActuatorGivesTheFaceNearestNeutral) {
  const ControllerModel& m = rig("hobby").built.model;
  const MappingInverse inv = make_mapping_inverse(m);
  MappingInverseWorkspace w = make_mapping_inverse_workspace(inv);
  const std::size_t l = *m.layout.find("eye_yaw_l"), r = *m.layout.find("eye_yaw_r");
  Face face = inv.neutral;
  face[l] = 0.3;
  face[r] = 0.1;
  const Positions p = map(m, face);
  Face back{};
  invert_mapping(inv, w, p, back);
  EXPECT_NEAR(back[l], 0.2, 1e-6);
  EXPECT_NEAR(back[r], 0.2, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Rigs, MappingInverseTest,
                         ::testing::Values("default", "hobby", "hobby_terms"));

// Positions the mapping cannot produce get the least-squares face: the one
// actuator that alone measures a signal decides it, clamped to its box.
TEST(MappingInverse, ClampsToTheAdmissibleBox) {
  const ControllerModel& m = rig("default").built.model;
  const MappingInverse inv = make_mapping_inverse(m);
  MappingInverseWorkspace w = make_mapping_inverse_workspace(inv);
  Face neutral = inv.neutral;
  Positions p = map(m, neutral);
  const std::size_t pan = *m.layout.find("neck_pan");
  std::size_t actuator = 0;
  while (m.actuators[actuator].name != "neck_pan") ++actuator;
  p[actuator] = m.actuators[actuator].limits.position_max;  // 65°, beyond the head's ±60°
  Face back{};
  const MappingInverseResult r = invert_mapping(inv, w, p, back);
  EXPECT_EQ(back[pan], inv.upper[pan]);
  EXPECT_GT(r.residual, 0.0);
}

// The second start triggers on the worst actuator's misfit, not on an average: among the
// default rig's ~20 fitted actuators one left 4x the 1e-4 threshold off keeps the RMS
// under it. Such a face is searched for (a fixed seed), and must be fitted by the restart.
// Such faces are rare (about one in 8000 random faces); a refit of the reduced model moves
// them, so the seed may need to change with one (seed 2 finds face 954).
TEST(MappingInverse, RestartsWhenOneActuatorAloneIsOff) {
  const ControllerModel& m = rig("default").built.model;
  const MappingInverse inv = make_mapping_inverse(m);
  MappingInverse first = inv;
  first.second_start = false;
  MappingInverseWorkspace w = make_mapping_inverse_workspace(inv);
  const int rows = static_cast<int>(m.actuators.size());
  const double threshold = 1e-4;  // kRestartResidual
  std::mt19937 rng(2);
  int found = -1;
  for (int sample = 0; sample < 3000 && found < 0; ++sample) {
    Face face = random_face(inv, rng);
    const Positions p = map(m, face);
    Face back{};
    const MappingInverseResult once = invert_mapping(first, w, p, back);
    const double worst_once = w.residual.head(rows).lpNorm<Eigen::Infinity>();
    if (!(worst_once > threshold && once.residual < threshold)) continue;
    found = sample;
    // An RMS (or squared-norm) trigger would have stopped here.
    EXPECT_LT(w.residual.head(rows).squaredNorm(), threshold);
    EXPECT_TRUE(needs_second_start({w.residual.data(), static_cast<std::size_t>(rows)}));
    const MappingInverseResult twice = invert_mapping(inv, w, p, back);
    EXPECT_GT(twice.iterations, once.iterations) << "no second start, sample " << sample;
    EXPECT_LE(w.residual.head(rows).lpNorm<Eigen::Infinity>(), threshold)
        << "sample " << sample << ": the worst actuator was " << worst_once << " off";
  }
  ASSERT_GE(found, 0) << "no face whose first descent leaves one actuator alone off";
  std::printf("face %d: one actuator off after the first descent\n", found);
}

TEST(MappingInverse, TheSecondStartTriggerIsTheWorstMisfitEitherSign) {
  std::vector<double> r(20, 0.9e-4);
  EXPECT_FALSE(needs_second_start(r));
  r[7] = -2e-4;  // RMS 9.8e-5: below the threshold
  EXPECT_TRUE(needs_second_start(r));
  r[7] = 2e-4;
  EXPECT_TRUE(needs_second_start(r));
  EXPECT_FALSE(needs_second_start({}));
}

}  // namespace
}  // namespace facectl
