// Thesis §3.2 checkable claims: a k = 1 distance constraint lands exactly at its rest
// length, and every constraint type reduces |C| when projected.
#include "facectl/face/constraints.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace facectl::face {
namespace {

Points random_points(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  Points p;
  for (int i = 0; i < n; ++i) p.push_back(Vec3(u(rng), u(rng), u(rng)));
  return p;
}

TEST(DistanceConstraint, StiffnessOneLandsExactlyAtRestLength) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 100; ++trial) {
    Points p = random_points(2, rng);
    DistanceConstraints s;
    s.add(0, 1, 0.013, 1.0);
    project(s, p, {1.0, 1.0});
    EXPECT_NEAR((p.get(0) - p.get(1)).norm(), 0.013, 1e-15);
  }
}

TEST(DistanceConstraint, MassWeightsSplitTheCorrection) {
  Points p;
  p.push_back(Vec3(0, 0, 0));
  p.push_back(Vec3(0.02, 0, 0));
  DistanceConstraints s;
  s.add(0, 1, 0.01, 1.0);
  project(s, p, {0.0, 1.0});  // particle 0 is pinned: only 1 moves
  EXPECT_EQ(p.get(0), Vec3(0, 0, 0));
  EXPECT_NEAR(p.x[1], 0.01, 1e-15);
}

TEST(DistanceConstraint, StiffnessScalesTheCorrection) {
  Points p;
  p.push_back(Vec3(0, 0, 0));
  p.push_back(Vec3(0.02, 0, 0));
  DistanceConstraints s;
  s.add(0, 1, 0.01, 0.5);
  project(s, p, {1.0, 1.0});
  EXPECT_NEAR((p.get(0) - p.get(1)).norm(), 0.015, 1e-15);
}

// Angle error wrapped to (−π, π].
double angle_error(double phi, double rest) {
  return std::remainder(phi - rest, 2 * M_PI);
}

TEST(BendingConstraint, ProjectionReducesViolation) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> ang(-3.1, 3.1);
  int tested = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Points p = random_points(4, rng);
    const double a0 = bending_angle(p, 0, 1, 2, 3);
    const double rest = ang(rng);
    if (std::abs(angle_error(a0, rest)) > 3.0) continue;  // C is near its ±π branch cut
    BendingConstraints s;
    s.add(0, 1, 2, 3, rest, 1.0);
    project(s, p, {1, 1, 1, 1});
    EXPECT_LT(std::abs(angle_error(bending_angle(p, 0, 1, 2, 3), rest)),
              std::abs(angle_error(a0, rest)))
        << trial;
    ++tested;
  }
  EXPECT_GT(tested, 300);
}

// A flat pair (|φ| = π) bent by 0.2 rad is driven back to flat; Müller's acos gradient
// vanishes there. The angle is signed, so the mirror-image fold is not a rest state.
TEST(BendingConstraint, FlatRestAndSignedAngle) {
  Points p;
  for (Vec3 v : {Vec3(0, 0, 0), Vec3(0, 0, 0.01), Vec3(0.01, 0, 0.005), Vec3(-0.01, 0, 0.005)})
    p.push_back(v);
  BendingConstraints s;
  s.add_at_rest(p, 0, 1, 2, 3, 1.0);
  EXPECT_NEAR(std::abs(s.rest[0]), M_PI, 1e-12);
  for (double bend : {0.2, -0.2}) {
    Points q = p;
    q.set(2, Vec3(0.01 * std::cos(bend), 0.01 * std::sin(bend), 0.005));
    const double before = std::abs(angle_error(bending_angle(q, 0, 1, 2, 3), s.rest[0]));
    EXPECT_NEAR(before, 0.2, 1e-12);
    for (int it = 0; it < 3; ++it) project(s, q, {1, 1, 1, 1});
    EXPECT_LT(std::abs(angle_error(bending_angle(q, 0, 1, 2, 3), s.rest[0])), 1e-3 * before);
  }
  BendingConstraints folded;
  folded.add(0, 1, 2, 3, 1.0, 1.0);
  EXPECT_NEAR(std::abs(angle_error(-1.0, folded.rest[0])), 2.0, 1e-12);  // −1 is not +1
}

TEST(AreaConstraint, ProjectionReducesViolation) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> area(1e-5, 3e-4);
  for (int trial = 0; trial < 200; ++trial) {
    Points p = random_points(3, rng);
    AreaConstraints s;
    s.add(0, 1, 2, area(rng), 1.0);
    const double before = area_value(s, 0, p);
    project(s, p, {1, 1, 1});
    EXPECT_LT(std::abs(area_value(s, 0, p)), std::abs(before)) << trial;
  }
}

// A closed octahedron, outward winding.
TriMesh octahedron(double r) {
  TriMesh m;
  for (Vec3 v : {Vec3(r, 0, 0), Vec3(-r, 0, 0), Vec3(0, r, 0), Vec3(0, -r, 0), Vec3(0, 0, r),
                 Vec3(0, 0, -r)})
    m.v.push_back(v);
  m.tris = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

TEST(VolumeConstraint, ProjectionReducesViolationAndInflationReachesTarget) {
  TriMesh m = octahedron(0.01);
  VolumeConstraint v = make_volume(m.v, m.tris, Vec3(0.003, -0.002, 0.001), 1.0);
  const double v0 = v.rest;
  EXPECT_GT(v0, 0);
  v.rest = 2 * v0;  // inflate (Figs. 3.7–3.8)
  Points grad;
  grad.resize(m.v.size());
  std::vector<double> w(m.v.size(), 1.0);
  double err = std::abs(volume_of(v, m.v) - v.rest);
  for (int it = 0; it < 20; ++it) {
    project(v, m.v, w, grad);
    const double e = std::abs(volume_of(v, m.v) - v.rest);
    EXPECT_LE(e, err + 1e-12 * v.rest);
    err = e;
  }
  EXPECT_NEAR(volume_of(v, m.v) / v.rest, 1.0, 1e-6);
}

TEST(VolumeConstraint, ClosedSurfaceVolumeIgnoresReferencePoint) {
  TriMesh m = octahedron(0.01);
  EXPECT_NEAR(make_volume(m.v, m.tris, Vec3::Zero(), 1).rest,
              make_volume(m.v, m.tris, Vec3(0.05, 0.02, -0.03), 1).rest, 1e-18);
}

TEST(Attachment, MovesTowardTargetByStiffness) {
  Points p, t;
  p.push_back(Vec3(0, 0, 0));
  t.push_back(Vec3(0.01, 0, 0));
  Attachments a;
  a.add(0, 0.2);
  project(a, p, {1.0}, t);
  EXPECT_NEAR(p.x[0], 0.002, 1e-15);
  project(a, p, {0.0}, t);  // infinite mass does not move
  EXPECT_NEAR(p.x[0], 0.002, 1e-15);
}

}  // namespace
}  // namespace facectl::face
