// Mandible mechanisms: the strokes are the strut lengths of the face model's
// mandible transform, forward kinematics inverts them across the envelope, and an
// unreachable target is clamped to the nearest reachable pose within the limits.
#include "control/mapping/mandible_mechanism.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "tests/support/mandible_mechanisms.hpp"
#include "tests/support/sample_count.hpp"

namespace facectl {
namespace {

using testing::default_head_axes;
using testing::proposed_mechanism;

constexpr double kDeg = std::numbers::pi / 180.0;

face::MandiblePose pose_deg_mm(double pitch, double yaw, double protrusion) {
  return {pitch * kDeg, yaw * kDeg, protrusion * 1e-3};
}

// Every grid pose of the default envelope (steps of 0.5° and 0.5 mm); DOFs the
// mechanism does not drive stay at 0.
std::vector<face::MandiblePose> envelope_grid(const MandibleMechanism& m) {
  std::vector<face::MandiblePose> out;
  const double yaw_max = m.driven[1] ? 5.0 : 0.0;
  const double prot_max = m.driven[2] ? 8.0 : 0.0;
  for (double p = -4.0; p <= 18.0 + 1e-9; p += 0.5)
    for (double y = -yaw_max; y <= yaw_max + 1e-9; y += 0.5)
      for (double d = 0.0; d <= prot_max + 1e-9; d += 0.5) out.push_back(pose_deg_mm(p, y, d));
  return out;
}

void expect_pose_near(const face::MandiblePose& a, const face::MandiblePose& b, double deg,
                      double mm) {
  EXPECT_NEAR(a.pitch_rad, b.pitch_rad, deg * kDeg);
  EXPECT_NEAR(a.yaw_rad, b.yaw_rad, deg * kDeg);
  EXPECT_NEAR(a.protrusion_m, b.protrusion_m, mm * 1e-3);
}

TEST(MandibleMechanism, StrokesAreTheStrutLengthsOfTheFaceModelsTransform) {
  for (std::size_t n : {3u, 2u}) {
    const MandibleMechanism m = proposed_mechanism(n);
    for (const face::MandiblePose& pose :
         {pose_deg_mm(0, 0, 0), pose_deg_mm(18, -5, 8), pose_deg_mm(-4, 5, 3)}) {
      MandibleStrokes s{};
      strokes(m, pose, s);
      face::MandiblePose driven = pose;
      if (!m.driven[2]) driven.protrusion_m = 0.0;
      const face::RigidTransform T = face::mandible_transform(m.axes, driven);
      for (std::size_t i = 0; i < n; ++i) {
        const double L = (m.strut[i].skull - T.apply(m.strut[i].mandible)).norm();
        EXPECT_NEAR(s[i], m.strut[i].stroke_at_rest + L - m.rest_length[i], 1e-15);
      }
    }
  }
}

TEST(MandibleMechanism, JacobianMatchesFiniteDifferences) {
  const MandibleMechanism m = proposed_mechanism(3);
  const MandibleVector q(10 * kDeg, -3 * kDeg, 0.004);
  MandibleStrokes s{};
  Eigen::Matrix3d J;
  strokes_and_jacobian(m, q, s, J);
  for (int k = 0; k < 3; ++k) {
    const double h = k == 2 ? 1e-7 : 1e-6;
    MandibleVector up = q, down = q;
    up[k] += h;
    down[k] -= h;
    MandibleStrokes su{}, sd{};
    strokes(m, to_pose(up), su);
    strokes(m, to_pose(down), sd);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(J(i, k), (su[i] - sd[i]) / (2 * h), 1e-7) << i << k;
  }
}

// The round trip pose → strokes → forward → pose holds to 0.01° and 0.01 mm
// over the whole envelope, from the rest pose as the guess.
TEST(MandibleMechanism, RoundTripAcrossTheEnvelope) {
  for (std::size_t n : {3u, 2u}) {
    const MandibleMechanism m = proposed_mechanism(n);
    const std::vector<face::MandiblePose> grid = envelope_grid(m);
    EXPECT_GT(grid.size(), n == 3 ? 16000u : 900u);
    double worst_deg = 0.0, worst_mm = 0.0;
    for (const face::MandiblePose& pose : grid) {
      MandibleStrokes s{};
      strokes(m, pose, s);
      const auto back = forward(m, s);
      ASSERT_TRUE(back.has_value()) << pose.pitch_rad / kDeg << " " << pose.yaw_rad / kDeg;
      worst_deg = std::max({worst_deg, std::fabs(back->pitch_rad - pose.pitch_rad) / kDeg,
                            std::fabs(back->yaw_rad - pose.yaw_rad) / kDeg});
      worst_mm = std::max(worst_mm, std::fabs(back->protrusion_m - pose.protrusion_m) * 1e3);
    }
    EXPECT_LT(worst_deg, 0.01) << n << " struts";
    EXPECT_LT(worst_mm, 0.01) << n << " struts";
    // Newton converges far tighter than the requirement.
    EXPECT_LT(worst_deg, 1e-6);
    EXPECT_LT(worst_mm, 1e-6);
  }
}

TEST(MandibleMechanism, ReachableTargetsAreUnchanged) {
  for (std::size_t n : {3u, 2u}) {
    const MandibleMechanism m = proposed_mechanism(n);
    for (const face::MandiblePose& pose : envelope_grid(m)) {
      MandibleStrokes out{}, expected{};
      const MandibleSolveResult r = solve(m, pose, out);
      strokes(m, pose, expected);
      ASSERT_FALSE(r.clamped);
      EXPECT_EQ(r.iterations, 0);
      EXPECT_EQ(r.achieved.pitch_rad, pose.pitch_rad);
      EXPECT_EQ(r.achieved.yaw_rad, pose.yaw_rad);
      EXPECT_EQ(r.achieved.protrusion_m, pose.protrusion_m);
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(out[i], expected[i]);
    }
  }
}

TEST(MandibleMechanism, DofsNotDrivenTakeTheirHeldValue) {
  const MandibleMechanism m = proposed_mechanism(2);
  MandibleStrokes a{}, b{};
  strokes(m, pose_deg_mm(10, 2, 0), a);
  strokes(m, pose_deg_mm(10, 2, 6), b);
  EXPECT_EQ(a, b);
  const MandibleSolveResult r = solve(m, pose_deg_mm(10, 2, 6), b);
  EXPECT_EQ(r.achieved.protrusion_m, 0.0);
  EXPECT_FALSE(r.clamped);
}

// The same mechanism with tighter stroke limits, so that much of the envelope
// is out of reach.
MandibleMechanism narrowed(std::size_t n) {
  const MandibleMechanism base = proposed_mechanism(n);
  std::array<MandibleStrut, 3> struts = base.strut;
  std::vector<MandibleDof> dofs(base.dof.begin(), base.dof.begin() + n);
  // Strut 0 (digastric) reaches about 9° of opening; the others a few mm either way.
  for (std::size_t i = 0; i < n; ++i) {
    struts[i].stroke = {struts[i].stroke_at_rest - (i == 0 ? 0.016 : 0.004),
                        struts[i].stroke_at_rest + (i == 0 ? 0.003 : 0.005)};
  }
  return make_mandible_mechanism(base.axes, dofs, std::span(struts.data(), n),
                                 MandibleEnvelope::design_default());
}

bool reachable(const MandibleMechanism& m, const MandibleVector& q, double slack = 0.0) {
  MandibleStrokes s{};
  strokes(m, to_pose(q), s);
  for (std::size_t i = 0; i < m.count; ++i)
    if (s[i] < m.strut[i].stroke.min - slack || s[i] > m.strut[i].stroke.max + slack) return false;
  return true;
}

double distance(const MandibleMechanism& m, const MandibleVector& a, const MandibleVector& b) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k)
    if (m.driven[k]) d2 += std::pow(m.weight[k] * (a[k] - b[k]), 2);
  return std::sqrt(d2);
}

// The nearest reachable pose by brute force: a grid of `step` metric units over
// the box centre ± half (driven DOFs only). Returns the best point and distance.
std::pair<MandibleVector, double> grid_search(const MandibleMechanism& m,
                                              const MandibleVector& target,
                                              const MandibleVector& centre, double half,
                                              double step) {
  MandibleVector best = centre;
  double best_d = std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(std::round(half / step));
  std::array<int, 3> span{};
  for (int k = 0; k < 3; ++k) span[k] = m.driven[k] ? n : 0;
  for (int i = -span[0]; i <= span[0]; ++i)
    for (int j = -span[1]; j <= span[1]; ++j)
      for (int l = -span[2]; l <= span[2]; ++l) {
        MandibleVector q = centre;
        const std::array<int, 3> idx = {i, j, l};
        for (int k = 0; k < 3; ++k) q[k] += idx[k] * step / m.weight[k];
        q = m.held_in(q);
        if (!reachable(m, q)) continue;
        const double d = distance(m, q, target);
        if (d < best_d) {
          best_d = d;
          best = q;
        }
      }
  return {best, best_d};
}

TEST(MandibleMechanism, UnreachableTargetsGoToTheNearestReachablePose) {
  for (std::size_t n : {3u, 2u}) {
    const MandibleMechanism m = narrowed(n);
    std::mt19937_64 rng(42 + n);
    std::uniform_real_distribution<double> pitch(-6, 22), yaw(-7, 7), prot(-2, 10);
    int clamped = 0;
    const long trials = testing::sample_count(24, 6);  // each runs three grid searches
    for (long trial = 0; trial < trials; ++trial) {
      const face::MandiblePose target = pose_deg_mm(pitch(rng), yaw(rng), prot(rng));
      MandibleStrokes out{};
      const MandibleSolveResult r = solve(m, target, out);
      // The strokes are within limits, and they are the achieved pose's.
      MandibleStrokes check{};
      strokes(m, r.achieved, check);
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_GE(out[i], m.strut[i].stroke.min);
        EXPECT_LE(out[i], m.strut[i].stroke.max);
        EXPECT_NEAR(out[i], check[i], 1e-11);  // Newton's tolerance
      }
      const MandibleVector goal = m.held_in(to_vector(target));
      if (!r.clamped) {
        EXPECT_TRUE(reachable(m, goal));
        continue;
      }
      ++clamped;
      EXPECT_FALSE(reachable(m, goal));
      EXPECT_LE(r.iterations, 10);
      const MandibleVector x = to_vector(r.achieved);
      EXPECT_NEAR(r.distance, distance(m, x, goal), 1e-12);
      // The achieved pose is on the boundary of the reachable set.
      double nearest_limit = 1.0;
      for (std::size_t i = 0; i < n; ++i)
        nearest_limit = std::min({nearest_limit, std::fabs(out[i] - m.strut[i].stroke.min),
                                  std::fabs(out[i] - m.strut[i].stroke.max)});
      EXPECT_LT(nearest_limit, 1e-9);
      // Brute force in the same metric: a coarse grid (0.5 unit) over a wide
      // box, then finer ones (0.05, 0.01 unit) around the best point so far.
      const auto coarse = grid_search(m, goal, MandibleVector(7 * kDeg, 0, 0.004), 16.0, 0.5);
      const auto fine = grid_search(m, goal, coarse.first, 1.0, 0.05);
      const auto finer = grid_search(m, goal, fine.first, 0.3, 0.01);
      // No reachable grid point is nearer than the solver's pose, and the
      // nearest grid point is as near to within the grid's resolution.
      EXPECT_LE(r.distance, fine.second + 1e-9);
      EXPECT_LE(r.distance, finer.second + 1e-9);
      EXPECT_LT(finer.second, r.distance + 0.01);
    }
    EXPECT_GT(clamped, trials * 2 / 3) << n << " struts";  // 16 of 24
  }
}

TEST(MandibleMechanism, ClampingIsDeterministic) {
  const MandibleMechanism m = narrowed(3);
  MandibleStrokes a{}, b{};
  const MandibleSolveResult ra = solve(m, pose_deg_mm(17, 4.5, 7), a);
  const MandibleSolveResult rb = solve(m, pose_deg_mm(17, 4.5, 7), b);
  EXPECT_EQ(a, b);
  EXPECT_EQ(ra.achieved.pitch_rad, rb.achieved.pitch_rad);
  EXPECT_EQ(ra.iterations, rb.iterations);
}

TEST(MandibleMechanism, NonFiniteTargetGoesToRest) {
  const MandibleMechanism m = proposed_mechanism(3);
  MandibleStrokes out{};
  const MandibleSolveResult r = solve(m, {std::nan(""), 0.0, 0.0}, out);
  EXPECT_TRUE(r.clamped);
  expect_pose_near(r.achieved, {}, 0.0, 0.0);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(out[i], m.strut[i].stroke_at_rest);
}

TEST(MandibleMechanism, ProposedGeometryIsWellConditioned) {
  for (std::size_t n : {3u, 2u}) {
    const MandibleMechanism m = proposed_mechanism(n);
    const MandibleConditioning c = conditioning(m, MandibleEnvelope::design_default(), 21);
    EXPECT_LT(c.worst_condition, 3.5) << n;
    EXPECT_GT(c.smallest_singular, 0.5) << n;  // mm of stroke per degree or mm
  }
}

TEST(MandibleMechanism, RejectsBadMechanisms) {
  const MandibleMechanism good = proposed_mechanism(3);
  const std::array<MandibleDof, 3> dofs = {MandibleDof::kPitch, MandibleDof::kYaw,
                                           MandibleDof::kProtrusion};
  const auto env = MandibleEnvelope::design_default();
  const auto make = [&](std::array<MandibleStrut, 3> s, std::span<const MandibleDof> d) {
    return make_mandible_mechanism(good.axes, d, std::span(s.data(), d.size()), env);
  };
  auto expect_rejected = [&](std::array<MandibleStrut, 3> s, std::span<const MandibleDof> d,
                             const std::string& words) {
    try {
      make(s, d);
      ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  EXPECT_NO_THROW(make(good.strut, dofs));
  expect_rejected(good.strut, std::span(dofs.data(), 1), "2 or 3 struts");
  const std::array<MandibleDof, 3> twice = {MandibleDof::kPitch, MandibleDof::kYaw,
                                            MandibleDof::kYaw};
  expect_rejected(good.strut, twice, "driven twice");
  auto s = good.strut;
  s[1].mandible = s[1].skull;
  expect_rejected(s, dofs, "less than 1 mm apart");
  s = good.strut;
  s[2].stroke = {0.02, 0.01};
  expect_rejected(s, dofs, "min < max");
  s = good.strut;
  s[0].stroke_at_rest = 0.049;
  expect_rejected(s, dofs, "rest pose");
  // The two pterygoid struts on one side: yaw and protrusion no longer separate.
  s = good.strut;
  s[2] = s[1];
  s[2].mandible.x() += 0.002;
  expect_rejected(s, dofs, "ill-conditioned");
}

}  // namespace
}  // namespace facectl
