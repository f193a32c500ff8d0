// A mesh renumbered by its geometry (canonical_mesh.hpp): the same surface in any vertex and
// face order gives the same canonical mesh, each face keeps its winding, and `original`
// maps back to the input's numbering.
#include "facectl/face/canonical_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "test_heads.hpp"

namespace facectl::face {
namespace {

// A 4 x 3 grid of points on a bumpy sheet, two triangles a cell, counter-clockwise seen
// from +z.
TriMesh grid() {
  TriMesh m;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) m.v.push_back(Vec3(i, j, 0.1 * ((i * 7 + j * 3) % 5)));
  for (int j = 0; j + 1 < 3; ++j)
    for (int i = 0; i + 1 < 4; ++i) {
      const int a = 4 * j + i;
      m.tris.push_back({a, a + 1, a + 5});
      m.tris.push_back({a, a + 5, a + 4});
    }
  return m;
}

Vec3 normal(const Points& v, const Tri& t) {
  const auto p = [&](int i) { return v.get(static_cast<std::size_t>(i)); };
  return (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
}

TEST(CanonicalMesh, AnyNumberingGivesTheSameMeshWithItsWinding) {
  const TriMesh m = grid();
  const CanonicalMesh c = canonical_mesh(m);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const TriMesh s = testing::renumbered(m, seed, true).mesh;
    const CanonicalMesh d = canonical_mesh(s);
    EXPECT_EQ(d.mesh.v.x, c.mesh.v.x);
    EXPECT_EQ(d.mesh.v.y, c.mesh.v.y);
    EXPECT_EQ(d.mesh.v.z, c.mesh.v.z);
    EXPECT_EQ(d.mesh.tris, c.mesh.tris);
    // original maps to the same point of the shuffled input.
    for (std::size_t k = 0; k < d.original.size(); ++k)
      EXPECT_EQ(s.v.get(static_cast<std::size_t>(d.original[k])), d.mesh.v.get(k));
    std::vector<int> all(d.original.size());
    std::iota(all.begin(), all.end(), 0);
    to_original_indices(d, all);
    EXPECT_EQ(all, d.original);
  }
  // Every face faces +z as it did: the rotation kept the winding.
  ASSERT_EQ(c.mesh.tris.size(), m.tris.size());
  for (const Tri& t : c.mesh.tris) EXPECT_GT(normal(c.mesh.v, t).z(), 0);
  EXPECT_TRUE(std::is_sorted(c.mesh.tris.begin(), c.mesh.tris.end()));
  for (const Tri& t : c.mesh.tris) EXPECT_EQ(t[0], *std::min_element(t.begin(), t.end()));
}

}  // namespace
}  // namespace facectl::face
