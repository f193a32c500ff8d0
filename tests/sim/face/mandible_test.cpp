// Mandible of thesis §5.2 with the errata fixed: rotations leave their axis points fixed,
// protrusion moves every jaw vertex by exactly d, the composition order and signs are
// the documented ones, and the lower teeth follow the jaw.
#include "control/face/mandible.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "default_head.hpp"

namespace facectl::face {
namespace {

using testing::default_model;

constexpr double kDeg = std::numbers::pi / 180;

Vec3 landmark(const char* name) {
  const FaceModel& m = default_model();
  return landmark_position(m, m.skin.v, m.landmark_index(name));
}

TEST(Mandible, RodriguesMatchesAngleAxis) {
  const Vec3 u = Vec3(0.3, -0.5, 0.8).normalized();
  for (double a : {-1.0, 0.1, 0.7, 2.5})
    EXPECT_TRUE(rodrigues(u, a).isApprox(Eigen::AngleAxisd(a, u).toRotationMatrix(), 1e-14));
  // Erratum 11: element (3,1) is xz(1−c) − ys.
  const double a = 0.4, c = std::cos(a), s = std::sin(a);
  EXPECT_NEAR(rodrigues(u, a)(2, 0), u.x() * u.z() * (1 - c) - u.y() * s, 1e-15);
}

TEST(Mandible, PitchLeavesTheCondylesFixed) {
  const MandibleAxes& ax = default_model().axes;
  for (double p : {-4.0, 10.0, 18.0}) {
    RigidTransform T = mandible_transform(ax, {p * kDeg, 0, 0});
    EXPECT_LT((T.apply(landmark("fdp_2_13")) - landmark("fdp_2_13")).norm(), 1e-12);
    EXPECT_LT((T.apply(landmark("fdp_2_14")) - landmark("fdp_2_14")).norm(), 1e-12);
    EXPECT_GT((T.apply(landmark("fdp_2_10")) - landmark("fdp_2_10")).norm(), 1e-3);
  }
}

TEST(Mandible, YawLeavesItsAxisPointsFixed) {
  const MandibleAxes& ax = default_model().axes;
  const Vec3 mid = 0.5 * (landmark("fdp_2_13") + landmark("fdp_2_14"));
  for (double y : {-5.0, 5.0}) {
    RigidTransform T = mandible_transform(ax, {0, y * kDeg, 0});
    EXPECT_LT((T.apply(mid) - mid).norm(), 1e-12);
    EXPECT_LT((T.apply(landmark("fdp_11_4")) - landmark("fdp_11_4")).norm(), 1e-12);
  }
}

TEST(Mandible, SignConventions) {
  const MandibleAxes& ax = default_model().axes;
  const Vec3 chin = landmark("fdp_2_10");
  EXPECT_LT(mandible_transform(ax, {10 * kDeg, 0, 0}).apply(chin).y(), chin.y() - 0.005);  // opens
  EXPECT_GT(mandible_transform(ax, {0, 5 * kDeg, 0}).apply(chin).x(), chin.x() + 0.002);   // to +x
  EXPECT_GT(mandible_transform(ax, {0, 0, 0.004}).apply(chin).z(), chin.z() + 0.002);  // forward
}

TEST(Mandible, CompositionIsPitchThenYawThenProtrusion) {
  const MandibleAxes& ax = default_model().axes;
  const MandiblePose pose{12 * kDeg, -4 * kDeg, 0.006};
  const Vec3 v = landmark("fdp_2_1");
  Vec3 expect = rotation_about_line(ax.pitch_point, ax.pitch_axis, pose.pitch_rad).apply(v);
  expect = rotation_about_line(ax.yaw_point, ax.yaw_axis, pose.yaw_rad).apply(expect);
  expect += pose.protrusion_m * ax.protrusion_dir;
  EXPECT_LT((mandible_transform(ax, pose).apply(v) - expect).norm(), 1e-14);
  // The other order differs, so the test can tell.
  Vec3 other = rotation_about_line(ax.yaw_point, ax.yaw_axis, pose.yaw_rad).apply(v);
  other = rotation_about_line(ax.pitch_point, ax.pitch_axis, pose.pitch_rad).apply(other);
  EXPECT_GT((other + pose.protrusion_m * ax.protrusion_dir - expect).norm(), 1e-5);
}

TEST(Mandible, ProtrusionMovesEveryJawVertexByD) {
  const FaceModel& m = default_model();
  FaceData d = make_face_data(m);
  std::vector<double> c(m.spec.commanded.size(), 0.0);
  FaceInput in;
  in.contractions = c;
  in.jaw.protrusion_m = 0.005;
  step_face(m, d, in);
  ASSERT_FALSE(m.mandible_vertices.empty());
  std::vector<char> jaw(m.skull.v.size(), 0);
  for (int v : m.mandible_vertices) jaw[v] = 1;
  for (std::size_t v = 0; v < m.skull.v.size(); ++v) {
    const Vec3 delta = d.skull.get(v) - m.skull.v.get(v);
    if (jaw[v]) {
      EXPECT_NEAR(delta.norm(), 0.005, 1e-12);
      EXPECT_NEAR(delta.normalized().dot(m.axes.protrusion_dir), 1.0, 1e-9);
    } else {
      EXPECT_EQ(delta.norm(), 0.0);  // the cranium never moves
    }
  }
  for (std::size_t i = 0; i < m.lower_teeth.points.size(); ++i)  // lower teeth follow
    EXPECT_NEAR((d.lower_teeth.points[i] - m.lower_teeth.points[i]).norm(), 0.005, 1e-12);
}

TEST(Mandible, JawVerticesAreTheLowerFaceOnly) {
  const FaceModel& m = default_model();
  std::vector<char> jaw(m.skull.v.size(), 0);
  for (int v : m.mandible_vertices) jaw[v] = 1;
  EXPECT_TRUE(jaw[152]);  // chin
  EXPECT_TRUE(jaw[14]);   // lower inner lip
  EXPECT_FALSE(jaw[13]);  // upper inner lip
  EXPECT_FALSE(jaw[4]);   // nose tip
}

}  // namespace
}  // namespace facectl::face
