// A surface point keeps its barycentric coordinates and so stays on its triangle while
// the triangle deforms (thesis Fig. 4.1).
#include "facectl/face/surface_point.hpp"

#include <gtest/gtest.h>

#include <random>

namespace facectl::face {
namespace {

TEST(SurfacePoint, StaysOnItsDeformingTriangle) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05), b(0.0, 1.0);
  Points tri;
  tri.resize(3);
  for (int trial = 0; trial < 500; ++trial) {
    double t1 = b(rng), t2 = b(rng) * (1 - t1);
    SurfacePoint sp{Layer::kSkull, 0, 1, 2, 1 - t1 - t2, t1, t2};
    for (int k = 0; k < 3; ++k) tri.set(k, Vec3(u(rng), u(rng), u(rng)));
    const Vec3 p = sp.position(tri);
    const Vec3 a = tri.get(0), e1 = tri.get(1) - a, e2 = tri.get(2) - a;
    const Vec3 n = e1.cross(e2).normalized();
    EXPECT_NEAR(n.dot(p - a), 0.0, 1e-15);  // in the triangle's plane
    // Recover the coordinates by ray casting along the normal: inside, and unchanged.
    double uu, vv;
    const double t = ray_triangle(p + 0.01 * n, -n, a, tri.get(1), tri.get(2), uu, vv);
    ASSERT_NEAR(t, 0.01, 1e-12);
    EXPECT_NEAR(uu, t1, 1e-9);
    EXPECT_NEAR(vv, t2, 1e-9);
  }
}

TEST(SurfacePoint, FrameIsOrthonormalWithTheTriangleNormal) {
  Points tri;
  tri.push_back(Vec3(0, 0, 0));
  tri.push_back(Vec3(0.01, 0, 0));
  tri.push_back(Vec3(0, 0.02, 0));
  SurfacePoint sp{Layer::kSkull, 0, 1, 2, 1, 0, 0};
  Mat3 F = sp.frame(tri);
  EXPECT_TRUE((F.transpose() * F).isIdentity(1e-12));
  EXPECT_TRUE(F.col(2).isApprox(Vec3(0, 0, 1)));
}

}  // namespace
}  // namespace facectl::face
