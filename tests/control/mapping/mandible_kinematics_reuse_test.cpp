// What the tick's jaw kinematics keep between calls changes nothing but the work:
// kept rotations (MandibleRotations) and Newton's kept linearisation
// (MandibleLinearisation) give the bits of a solve from scratch.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "control/mapping/mandible_mechanism.hpp"
#include "tests/support/mandible_mechanisms.hpp"

namespace facectl {
namespace {

using testing::proposed_mechanism;

constexpr double kDeg = std::numbers::pi / 180.0;

// A path that holds some angles and changes others, including yaw's sign of zero.
std::vector<face::MandiblePose> path() {
  std::vector<face::MandiblePose> out;
  for (int k = 0; k < 40; ++k) out.push_back({(1.0 + 0.25 * k) * kDeg, 0.0, 0.0});
  out.push_back({out.back().pitch_rad, -0.0, 1e-3});
  for (int k = 0; k < 40; ++k) out.push_back({out.back().pitch_rad, (k % 7 - 3) * kDeg, 2e-3});
  return out;
}

TEST(MandibleKinematicsReuse, KeptRotationsGiveTheStrokesOfAFreshSolve) {
  for (std::size_t n : {3u, 2u}) {
    const MandibleMechanism m = proposed_mechanism(n);
    MandibleRotations kept;
    for (const face::MandiblePose& pose : path()) {
      MandibleStrokes fresh{}, reused{};
      const MandibleSolveResult a = solve(m, pose, fresh);
      const MandibleSolveResult b = solve(m, pose, reused, &kept);
      EXPECT_EQ(fresh, reused) << n << " struts, pitch " << pose.pitch_rad;
      EXPECT_EQ(a.clamped, b.clamped);
      EXPECT_TRUE(std::signbit(kept.yaw_rad) == std::signbit(m.driven[1] ? pose.yaw_rad : 0.0));
    }
  }
}

TEST(MandibleKinematicsReuse, WarmForwardGivesTheAnswerOfAColdOne) {
  const MandibleMechanism m = proposed_mechanism(3);
  MandibleLinearisation warm(to_vector({}));
  face::MandiblePose last{};
  for (const face::MandiblePose& pose : path()) {
    MandibleStrokes s{};
    strokes(m, pose, s);
    const auto cold = forward(m, s, last, 30, 1e-8);
    const auto hot = forward(m, s, warm, 30, 1e-8);
    ASSERT_TRUE(cold && hot);
    EXPECT_EQ(to_vector(*cold), to_vector(*hot));
    EXPECT_TRUE(warm.evaluated);
    EXPECT_EQ(warm.pose, to_vector(*hot));
    last = *cold;
  }
  // A failed solve leaves the warm start as it was.
  const MandibleLinearisation before = warm;
  const MandibleStrokes unreachable = {1.0, -1.0, 1.0};
  EXPECT_FALSE(forward(m, unreachable, warm, 30, 1e-8));
  EXPECT_EQ(warm.pose, before.pose);
  EXPECT_EQ(warm.strokes, before.strokes);
  EXPECT_EQ(warm.jacobian, before.jacobian);
}

}  // namespace
}  // namespace facectl
