// Whole-frame properties of the layered solver (§5.7): teeth contacts, robustness under
// long random contraction sequences at two mesh scales, determinism, no allocation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "alloc_counter.hpp"
#include "default_head.hpp"
#include "tests/support/sample_count.hpp"

namespace facectl::face {
namespace {

using testing::default_model;
using testing::default_spec;

constexpr double kDeg = M_PI / 180;

TEST(FaceStep, NeutralInputKeepsTheRestShape) {
  const FaceModel& m = default_model();
  FaceData d = make_face_data(m);
  std::vector<double> c(m.spec.commanded.size(), 0.0);
  FaceInput in;
  in.contractions = c;
  for (int f = 0; f < 50; ++f) step_face(m, d, in);
  for (std::size_t i = 0; i < d.skin_x.size(); ++i)
    ASSERT_LT((d.skin_x.get(i) - m.skin.v.get(i)).norm(), 1e-7) << i;  // round-off only
}

// The anchors on the skull away from the jaw get their targets once, at reset: every
// anchor is in exactly one list, and those supports stay put under jaw and muscles.
TEST(FaceStep, FixedSkullAnchorsHaveSupportsThatNeverMove) {
  const FaceModel& m = default_model();
  std::vector<int> seen(m.anchor_support.size(), 0);
  for (const auto* list : {&m.anchors_on_muscles, &m.anchors_on_jaw, &m.anchors_on_fixed_skull})
    for (int i : *list) ++seen[i];
  for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "anchor " << i;
  ASSERT_FALSE(m.anchors_on_fixed_skull.empty());
  ASSERT_FALSE(m.anchors_on_jaw.empty());
  FaceData d = make_face_data(m);
  std::vector<double> c(m.spec.commanded.size(), 0.5);
  FaceInput in;
  in.contractions = c;
  in.jaw = {15 * kDeg, 4 * kDeg, 0.006};
  for (int f = 0; f < 20; ++f) step_face(m, d, in);
  for (int i : m.anchors_on_fixed_skull) {
    const SurfacePoint& sp = m.anchor_support[i];
    ASSERT_EQ(sp.layer, Layer::kSkull);
    for (int v : {sp.i0, sp.i1, sp.i2})
      ASSERT_EQ((d.skull.get(v) - m.skull.v.get(v)).norm(), 0.0) << "anchor " << i;
  }
  // A jaw anchor's support does move, so the split is not vacuous.
  const SurfacePoint& jaw = m.anchor_support[m.anchors_on_jaw.front()];
  EXPECT_GT((d.skull.get(jaw.i0) - m.skull.v.get(jaw.i0)).norm() +
                (d.skull.get(jaw.i1) - m.skull.v.get(jaw.i1)).norm() +
                (d.skull.get(jaw.i2) - m.skull.v.get(jaw.i2)).norm(),
            1e-4);
}

// The anchors are per unit skin area: a finer variant's vertices hold smaller shares of the
// skin, so their anchors are weaker in proportion and the total stays that of the base mesh.
TEST(FaceStep, AnchorStiffnessIsPerUnitSkinArea) {
  const FaceModel& base = default_model();
  const FaceModel fine = build_face_model(default_spec(), 1466);
  ASSERT_GT(fine.anchors.size(), 3 * base.anchors.size());
  double sum_base = 0, sum_fine = 0;
  for (double k : base.anchors.k) {
    ASSERT_EQ(k, default_spec().skin.anchor);  // the base mesh keeps the head's value
    sum_base += k;
  }
  for (double k : fine.anchors.k) sum_fine += k;
  EXPECT_NEAR(sum_fine, sum_base, 1e-9 * sum_base);
}

TEST(TeethCollision, NoSkinVertexEndsAFrameInsideATeethHull) {
  HeadSpec spec = default_spec();
  spec.teeth_inset = -0.004;  // teeth pushed through the lips: contacts are certain
  const FaceModel m = build_face_model(spec);
  std::vector<double> c(m.spec.commanded.size(), 0.0);
  c[m.spec.commanded.size() - 1] = 0.4;  // orbicularis oris presses the lips
  FaceInput in;
  in.contractions = c;
  in.jaw.pitch_rad = 6 * kDeg;
  in.jaw.yaw_rad = 3 * kDeg;

  FaceData off = make_face_data(m);
  in.teeth_collision = false;
  for (int f = 0; f < 40; ++f) step_face(m, off, in);
  ASSERT_GT(skin_vertices_inside_teeth(m, off, 1e-6), 0) << "the scenario must penetrate";

  FaceData on = make_face_data(m);
  in.teeth_collision = true;
  for (int f = 0; f < 40; ++f) {
    step_face(m, on, in);
    ASSERT_EQ(skin_vertices_inside_teeth(m, on, 1e-6), 0) << "frame " << f;
  }
  EXPECT_GT(on.hits, 0);
}

// Random contraction sequence: a new random target every 40 frames, eased toward.
// Returns the number of (triangle, frame) inversions; fails at once on a NaN.
int soak(const FaceModel& m, int frames, unsigned seed) {
  FaceData d = make_face_data(m);
  const std::size_t n = m.spec.commanded.size();
  std::vector<double> c(n, 0.0), goal(n, 0.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  FaceInput in;
  in.contractions = c;
  MandiblePose jaw_goal;
  std::vector<Vec3> rest_n;
  for (const Tri& t : m.skin.tris)
    rest_n.push_back(
        (m.skin.v.get(t[1]) - m.skin.v.get(t[0])).cross(m.skin.v.get(t[2]) - m.skin.v.get(t[0])));
  int inverted = 0;
  for (int f = 0; f < frames; ++f) {
    if (f % 40 == 0) {
      for (auto& g : goal) g = u(rng) < 0.4 ? u(rng) : 0.0;
      jaw_goal = {(-4 + 22 * u(rng)) * kDeg, (-5 + 10 * u(rng)) * kDeg, 0.008 * u(rng)};
      in.eyelid_closure[0] = u(rng);
      in.eyelid_closure[1] = u(rng);
    }
    for (std::size_t k = 0; k < n; ++k) c[k] += 0.1 * (goal[k] - c[k]);
    in.jaw.pitch_rad += 0.1 * (jaw_goal.pitch_rad - in.jaw.pitch_rad);
    in.jaw.yaw_rad += 0.1 * (jaw_goal.yaw_rad - in.jaw.yaw_rad);
    in.jaw.protrusion_m += 0.1 * (jaw_goal.protrusion_m - in.jaw.protrusion_m);
    step_face(m, d, in);
    for (std::size_t i = 0; i < d.skin_x.size(); ++i)
      if (!std::isfinite(d.skin_x.x[i] + d.skin_x.y[i] + d.skin_x.z[i])) {
        ADD_FAILURE() << "NaN/inf skin at frame " << f;
        return -1;
      }
    for (std::size_t i = 0; i < d.muscles.size(); ++i)
      if (!std::isfinite(d.muscles.x[i] + d.muscles.y[i] + d.muscles.z[i])) {
        ADD_FAILURE() << "NaN/inf muscle at frame " << f;
        return -1;
      }
    for (std::size_t t = 0; t < m.skin.tris.size(); ++t) {
      const Tri& tr = m.skin.tris[t];
      const Vec3 nn = (d.skin_x.get(tr[1]) - d.skin_x.get(tr[0]))
                          .cross(d.skin_x.get(tr[2]) - d.skin_x.get(tr[0]));
      inverted += nn.dot(rest_n[t]) <= 0;
    }
  }
  return inverted;
}

// Frames of each soak: a tenth under the sanitizers (tests/support/sample_count.hpp).
const int kSoakFrames = static_cast<int>(facectl::testing::sample_count(2000));

TEST(Soak, RandomContractionsNeverProduceNaNAtTwoScales) {
  EXPECT_GE(soak(default_model(), kSoakFrames, 5), 0);
  EXPECT_GE(soak(build_face_model(default_spec(), 1500), kSoakFrames / 2, 6), 0);
}

// The skin may fold where neighbouring vertices ride on different muscles, but no
// triangle may turn over: the no-inversion constraint and the end-of-frame untangling
// (docs/FACE_MODEL.md, Solver) keep every triangle within 90° of its rest normal.
TEST(Soak, RandomContractionsNeverInvertATriangleAtTwoScales) {
  EXPECT_EQ(soak(default_model(), kSoakFrames, 5), 0) << "inverted triangle-frames at 468 vertices";
  EXPECT_EQ(soak(build_face_model(default_spec(), 1500), kSoakFrames / 2, 6), 0)
      << "inverted triangle-frames at 1500 vertices";
}

TEST(FaceStep, DeterministicBitForBit) {
  const FaceModel& m = default_model();
  std::vector<double> c(m.spec.commanded.size(), 0.0);
  for (std::size_t k = 0; k < c.size(); ++k) c[k] = 0.05 * static_cast<double>(k % 7);
  FaceInput in;
  in.contractions = c;
  in.jaw = {8 * kDeg, 2 * kDeg, 0.002};
  FaceData a = make_face_data(m), b = make_face_data(m);
  for (int f = 0; f < 100; ++f) step_face(m, a, in);
  for (int f = 0; f < 100; ++f) step_face(m, b, in);
  ASSERT_EQ(std::memcmp(a.skin_x.x.data(), b.skin_x.x.data(), a.skin_x.size() * sizeof(double)), 0);
  ASSERT_EQ(std::memcmp(a.skin_x.y.data(), b.skin_x.y.data(), a.skin_x.size() * sizeof(double)), 0);
  ASSERT_EQ(std::memcmp(a.skin_x.z.data(), b.skin_x.z.data(), a.skin_x.size() * sizeof(double)), 0);
}

// SolverPasses::skin stands in for the head's skin_iterations, bit for bit; muscle passes
// repeat the muscles' frame update.
TEST(FaceStep, SolverPassesOverrideTheHeadsIterations) {
  const FaceModel& m = default_model();
  HeadSpec spec2 = default_spec();
  spec2.skin_iterations = 3;
  const FaceModel m2 = build_face_model(spec2);
  std::vector<double> c(m.spec.commanded.size(), 0.0);
  for (std::size_t k = 0; k < c.size(); ++k) c[k] = 0.1 * static_cast<double>(k % 9);
  FaceInput in;
  in.contractions = c;
  in.jaw = {6 * kDeg, -2 * kDeg, 0.001};
  FaceData a = make_face_data(m), b = make_face_data(m2), one = make_face_data(m);
  for (int f = 0; f < 40; ++f) {
    step_face(m, a, in, {.skin = 3, .muscle = 1});
    step_face(m2, b, in);
    step_face(m, one, in);
  }
  const std::size_t bytes = a.skin_x.size() * sizeof(double);
  EXPECT_EQ(std::memcmp(a.skin_x.x.data(), b.skin_x.x.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(a.skin_x.z.data(), b.skin_x.z.data(), bytes), 0);
  EXPECT_NE(std::memcmp(a.skin_x.x.data(), one.skin_x.x.data(), bytes), 0);

  // Two muscle passes in one frame are two frames of the muscles alone.
  FaceData twice = make_face_data(m), apart = make_face_data(m);
  step_face(m, twice, in, {.skin = 0, .muscle = 2});
  step_skull_and_muscles(m, apart, in);
  step_skull_and_muscles(m, apart, in);
  const std::size_t mb = twice.muscles.size() * sizeof(double);
  EXPECT_EQ(std::memcmp(twice.muscles.y.data(), apart.muscles.y.data(), mb), 0);
}

TEST(FaceStep, StepDoesNotAllocate) {
  const FaceModel& m = default_model();
  FaceData d = make_face_data(m);
  std::vector<double> c(m.spec.commanded.size(), 0.3);
  FaceInput in;
  in.contractions = c;
  in.jaw = {10 * kDeg, 3 * kDeg, 0.003};
  in.eyelid_closure[0] = 0.5;
  step_face(m, d, in);  // warm
  testing::arm_alloc_counter();
  for (int f = 0; f < 20; ++f) step_face(m, d, in);
  step_face(m, d, in, {.skin = 4, .muscle = 4});
  EXPECT_EQ(testing::disarm_alloc_counter(), 0);
}

}  // namespace
}  // namespace facectl::face
