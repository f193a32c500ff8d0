// Higher-resolution variants keep the surface and every landmark vertex.
#include "facectl/face/subdivision.hpp"

#include <gtest/gtest.h>

#include "default_head.hpp"

namespace facectl::face {
namespace {

TEST(Subdivision, ReachesTheThesisSizesAndKeepsBaseVertices) {
  const FaceModel& base = testing::default_model();
  for (std::size_t target : {1466u, 2502u, 4904u}) {
    Refined r = refine_to_vertex_count(base.skin, target);
    EXPECT_EQ(r.mesh.v.size(), target);
    for (std::size_t i = 0; i < base.skin.v.size(); ++i)
      ASSERT_EQ(r.mesh.v.get(i), base.skin.v.get(i));
    for (std::size_t i = base.skin.v.size(); i < r.mesh.v.size(); ++i) {  // midpoints
      const auto [a, b] = r.parents[i];
      ASSERT_LT((r.mesh.v.get(i) - 0.5 * (r.mesh.v.get(a) + r.mesh.v.get(b))).norm(), 1e-15);
    }
    // Same surface area, still a manifold with the same openings.
    auto area = [](const TriMesh& m) {
      double s = 0;
      for (const Tri& t : m.tris)
        s += 0.5 * (m.v.get(t[1]) - m.v.get(t[0])).cross(m.v.get(t[2]) - m.v.get(t[0])).norm();
      return s;
    };
    EXPECT_NEAR(area(r.mesh), area(base.skin), 1e-12);
    EXPECT_EQ(boundary_loops(r.mesh.tris).size(), boundary_loops(base.skin.tris).size());
  }
}

TEST(Subdivision, DefaultHeadHasMouthAndEyeOpenings) {
  EXPECT_EQ(boundary_loops(testing::default_model().skin.tris).size(), 4u);  // outer, mouth, 2 eyes
}

}  // namespace
}  // namespace facectl::face
