// Facial motion cloning (motion_clone.hpp): a head cloned onto itself reproduces its
// displacements and the refinement leaves the commands alone (thesis Table 6.2); onto a
// warped copy (warped_head.hpp) the refinement fits the mapped displacements better than
// copying the commands; heads that do not correspond are refused, naming what differs.
#include "facectl/face/motion_clone.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>

#include "default_head.hpp"
#include "facectl/face/input_error.hpp"
#include "warped_head.hpp"

namespace facectl::face {
namespace {

namespace fs = std::filesystem;
using testing::default_library;
using testing::default_model;

MotionCloneOptions options() {
  MotionCloneOptions o;
  o.frames = FACECTL_CLONE_FRAMES;
  o.iterations = 2;
  return o;
}

const FaceModel& warped_model() {
  static const FaceModel model = [] {
    const fs::path dir = fs::temp_directory_path() / ("facectl_warped_" + std::to_string(getpid()));
    testing::write_warped_head(FACECTL_DEFAULT_HEAD_DIR, dir.string());
    FaceModel m = build_face_model(load_head_spec(dir.string()));
    fs::remove_all(dir);
    return m;
  }();
  return model;
}

TEST(MotionClone, SelfCloneReproducesTheDisplacementsAndMovesNothing) {
  const FaceModel& m = default_model();
  const CloneMap map = fit_clone_map(m, m);
  const MotionCloneOptions o = options();
  CloneWorkspace w = make_clone_workspace(m, m, map, o);
  for (const char* name : {"joy", "jaw_open", "wink"}) {
    SCOPED_TRACE(name);
    const Expression& e = *default_library().find(name);
    const ClonedPose c = clone_pose(m, m, map, e, o, w);
    EXPECT_LT(c.copy.rms_mm, 1e-6);
    EXPECT_LT(c.refined.percent, 1e-4);  // Table 6.2's worst is 0.28 %
    EXPECT_EQ(c.iterations, 0);
    EXPECT_EQ(c.pose.contractions, e.contractions);
    EXPECT_EQ(c.pose.jaw.pitch_rad, e.jaw.pitch_rad);
    EXPECT_EQ(c.pose.eyelid_closure[0], e.eyelid_closure[0]);
    EXPECT_GT(c.free_parameters, 0);
  }
}

TEST(MotionClone, RefinementBeatsThePlainCopyOnAWarpedHead) {
  const FaceModel &s = default_model(), &t = warped_model();
  const CloneMap map = fit_clone_map(s, t);
  const MotionCloneOptions o = options();
  CloneWorkspace w = make_clone_workspace(s, t, map, o);
  // refined/copy RMS measured 0.58 (pucker) and 0.61 (anger) at 120 frames, 0.62 and 0.62
  // at the sanitizer trees' 60; the bounds leave room for the solver's rounding. Joy gains
  // less (0.91 at 120 frames, 0.73 at 60), and sadness (0.91, 0.95; its copy is off by
  // only 0.12 mm at 60): their strongest muscles end at c = 1 on the warped head, which
  // needs more reach than the source's.
  for (const auto& [name, ratio] :
       {std::pair{"pucker", 0.75}, std::pair{"anger", 0.75}, std::pair{"joy", 0.97}}) {
    SCOPED_TRACE(name);
    const ClonedPose c = clone_pose(s, t, map, *default_library().find(name), o, w);
    EXPECT_GT(c.copy.rms_mm, 0.2);  // the warp changes how the copied commands move the face
    EXPECT_LT(c.refined.rms_mm, ratio * c.copy.rms_mm);
    std::printf("%s: copy %.3f mm, refined %.3f mm RMS\n", name, c.copy.rms_mm, c.refined.rms_mm);
    for (double x : c.pose.contractions) {
      EXPECT_GE(x, 0);
      EXPECT_LE(x, 1);
    }
    EXPECT_LE(c.pose.jaw.pitch_rad, o.jaw.pitch_max);
    EXPECT_LE(c.evaluations, 1 + o.iterations * (c.free_parameters + 4));
  }
}

// Known answer: on one head (the warped one, cloned onto itself, so G is the identity),
// the goals come from commands moved a known amount from where the refinement starts;
// the refinement must find those commands again. Measured at 120 frames: 0.199 mm RMS
// at the start (0.108 in the sanitizer trees' 60-frame runs), 9.2e-8 mm and every command
// within 1.9e-7 after 4 iterations; the bounds, 0.01 mm and 0.01, leave room for the
// sanitizer trees' shorter runs.
TEST(MotionClone, RefinementRecoversKnownCommandsOnTheSameHead) {
  const FaceModel& t = warped_model();
  const CloneMap map = fit_clone_map(t, t);
  MotionCloneOptions o = options();
  o.iterations = 6;
  CloneWorkspace w = make_clone_workspace(t, t, map, o);
  const Expression& start = *default_library().find("sadness");
  Expression known = start;
  double moved = 0;
  for (std::size_t i = 0; i < known.contractions.size(); ++i)
    if (known.contractions[i] > 0) {
      const double delta = known.contractions[i] > 0.5 ? -0.15 : 0.15;  // stays in (0, 1]
      known.contractions[i] += delta;
      moved = std::max(moved, std::abs(delta));
    }
  const Eigen::VectorXd goal = clone_goals(t, map, known, o, w);
  const ClonedPose c = refine_clone(t, map, goal, known, start, o, w);
  double worst = 0;
  for (std::size_t i = 0; i < known.contractions.size(); ++i)
    worst = std::max(worst, std::abs(c.pose.contractions[i] - known.contractions[i]));
  std::printf(
      "known answer: %d parameters moved %.2f; copy %.3f mm, refined %.2e mm RMS; "
      "worst command error %.2e after %d iterations\n",
      c.free_parameters, moved, c.copy.rms_mm, c.refined.rms_mm, worst, c.iterations);
  EXPECT_GT(c.free_parameters, 1);
  EXPECT_GT(c.copy.rms_mm, 0.05);  // the start is five times the bound below off
  EXPECT_LT(c.refined.rms_mm, 0.01);
  EXPECT_LT(worst, 0.01);
}

// A target whose head.yaml allows the lids only half closed: the copy and the result stay
// in that range (the range was [0, 1] whatever the head said).
TEST(MotionClone, KeepsTheEyelidsInTheTargetsRange) {
  const FaceModel& m = default_model();
  const CloneMap map = fit_clone_map(m, m);
  MotionCloneOptions o = options();
  o.eyelid[0] = {0.1, 0.5};
  o.eyelid[1] = {0, 0.4};
  CloneWorkspace w = make_clone_workspace(m, m, map, o);
  const ClonedPose c = clone_pose(m, m, map, *default_library().find("blink"), o, w);
  EXPECT_GT(c.copy.rms_mm, 0.1);  // blink closes the lids fully on the source
  for (int side = 0; side < 2; ++side) {
    EXPECT_GE(c.pose.eyelid_closure[side], o.eyelid[side].min);
    EXPECT_LE(c.pose.eyelid_closure[side], o.eyelid[side].max);
  }
  EXPECT_EQ(c.free_parameters, 2);
}

TEST(MotionClone, RefusesHeadsWhoseLandmarksDiffer) {
  FaceModel t = default_model();
  t.landmark_names[0] = "fdp_99_1";
  try {
    fit_clone_map(default_model(), t);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("landmark names"), std::string::npos) << what;
    EXPECT_NE(what.find("fdp_99_1"), std::string::npos) << what;
    EXPECT_NE(what.find(default_model().landmark_names[0]), std::string::npos) << what;
  }
}

TEST(MotionClone, RefusesHeadsWhoseMusclesDiffer) {
  FaceModel t = default_model();
  t.spec.commanded.back() = "orbicularis_oris_upper";
  try {
    fit_clone_map(default_model(), t);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("muscle names"), std::string::npos) << what;
    EXPECT_NE(what.find("orbicularis_oris_upper"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace facectl::face
