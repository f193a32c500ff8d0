// Skin stiffnesses carried across vertex densities (skin_density.hpp).
#include "facectl/face/skin_density.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "default_head.hpp"
#include "facectl/face/obj_io.hpp"
#include "facectl/face/subdivision.hpp"

namespace facectl::face {
namespace {

TEST(MeanVertexArea, CountsOnlyTheVerticesTrianglesUse) {
  TriMesh m;
  m.v.push_back(Vec3(0, 0, 0));
  m.v.push_back(Vec3(2, 0, 0));
  m.v.push_back(Vec3(2, 2, 0));
  m.v.push_back(Vec3(0, 2, 0));
  m.v.push_back(Vec3(9, 9, 9));  // loose
  m.tris = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_DOUBLE_EQ(mean_vertex_area(m), 1.0);  // 4 mm² over 4 used vertices
  EXPECT_EQ(mean_vertex_area(TriMesh{}), 0.0);
}

// A finer variant of the default skin (edge splitting, the same surface) has about
// 468/n of the base's area per vertex.
TEST(MeanVertexArea, FallsWithTheVertexCountOnTheSameSurface) {
  const HeadSpec& spec = testing::default_spec();
  const TriMesh base = read_obj(spec.skin_file, spec.skin_scale);
  const TriMesh fine = refine_to_vertex_count(base, 1466).mesh;
  const double ratio = mean_vertex_area(fine) / mean_vertex_area(base);
  EXPECT_NEAR(ratio, 468.0 / 1466.0, 0.02 * 468.0 / 1466.0);
}

// The weights the PBD fixed point balances are k/|∇C|²: relative to stretch, bending must
// grow as 1/ratio and the anchors shrink as ratio.
TEST(StiffnessForVertexArea, KeepsTheWeightsPerUnitArea) {
  const SkinStiffness k{.stretch = 0.15, .bending = 0.95, .area = 0.95, .anchor = 0.2};
  for (const double r : {0.1, 0.3, 1.0, 1.5, 4.0, 10.0}) {
    const SkinStiffness s = stiffness_for_vertex_area(k, r);
    EXPECT_NEAR((s.bending / s.stretch) / (k.bending / k.stretch), 1 / r, 1e-12) << r;
    EXPECT_NEAR((s.anchor / s.stretch) / (k.anchor / k.stretch), r, 1e-12) << r;
    EXPECT_NEAR((s.area / s.stretch) / (k.area / k.stretch), 1.0, 1e-12) << r;
    for (const double v : {s.stretch, s.bending, s.area, s.anchor}) EXPECT_LE(v, 1.0) << r;
    EXPECT_EQ(s.volume, k.volume);
    EXPECT_EQ(s.damping, k.damping);
    EXPECT_EQ(s.min_projected_area, k.min_projected_area);
  }
  const SkinStiffness same = stiffness_for_vertex_area(k, 1.0);
  EXPECT_EQ(same.stretch, k.stretch);
  EXPECT_EQ(same.bending, k.bending);
  EXPECT_EQ(same.anchor, k.anchor);
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(stiffness_for_vertex_area(k, bad), std::invalid_argument) << bad;
}

// On a denser skin (ratio < 1) bending, the largest, stays; the rest are lowered. A fit
// there and back gives the stiffnesses back.
TEST(StiffnessForVertexArea, DenserSkinKeepsBendingAndRoundTrips) {
  const SkinStiffness k{.stretch = 0.15, .bending = 0.95, .area = 0.95, .anchor = 0.2};
  const SkinStiffness s = stiffness_for_vertex_area(k, 0.4);
  EXPECT_NEAR(s.stretch, 0.15 * 0.4, 1e-12);
  EXPECT_NEAR(s.area, 0.95 * 0.4, 1e-12);
  EXPECT_NEAR(s.bending, 0.95, 1e-12);
  EXPECT_NEAR(s.anchor, 0.2 * 0.4 * 0.4, 1e-12);
  // 0.4 then 2.5: on the way back the largest weight is 0.38, so all four are scaled up.
  const SkinStiffness back = stiffness_for_vertex_area(stiffness_for_vertex_area(k, 0.4), 2.5);
  EXPECT_NEAR(back.stretch, k.stretch, 1e-12);
  EXPECT_NEAR(back.area, k.area, 1e-12);
  EXPECT_NEAR(back.bending, k.bending, 1e-12);
  EXPECT_NEAR(back.anchor, k.anchor, 1e-12);
}

}  // namespace
}  // namespace facectl::face
