// Paths along mesh edges (edge_paths.hpp): the contour joining of `face fit-head` where
// the new mesh is closed over an opening.
#include "facectl/face/edge_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace facectl::face {
namespace {

// A strip of unit squares, two rows: bottom vertices first + x0 .. first + x0 + n − 1 at
// y = 0, then the top row at y = 1.
void add_strip(TriMesh& m, int n, double x0) {
  const int first = static_cast<int>(m.v.size());
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < n; ++i) m.v.push_back(Vec3(x0 + i, row, 0));
  for (int i = 0; i + 1 < n; ++i) {
    const int a = first + i, t = first + n + i;
    m.tris.push_back({a, a + 1, t + 1});
    m.tris.push_back({a, t + 1, t});
  }
}

// A vertex duplicated at the same position and joined to its twin by a zero-length edge
// (a collapsed triangle, as exporters leave them): distances tie through the twin. The
// walk used to follow the tie into the twin and back forever.
TEST(EdgePath, ZeroLengthEdgesDoNotTrapThePath) {
  TriMesh m;
  m.v.push_back(Vec3(2, 0, 0));  // 0: the twin of vertex 3, listed first
  add_strip(m, 5, 0.0);          // 1..5 bottom, 6..10 top
  m.tris.push_back({3, 0, 8});   // zero-length edge 3–0
  for (const Adjacency& adj : {vertex_adjacency(m.v.size(), m.tris), path_adjacency(m.v, m.tris)}) {
    EXPECT_EQ(edge_path(m.v, adj, 1, 5), (std::vector<int>{1, 2, 3, 4}));
    EXPECT_EQ(edge_path(m.v, adj, 5, 1), (std::vector<int>{5, 4, 3, 2}));
    // From the twin: through the zero-length edge, not around it.
    EXPECT_EQ(edge_path(m.v, adj, 0, 5), (std::vector<int>{0, 3, 4}));
  }
}

// Two strips meeting along a seam of coincident vertices but sharing no edge (a UV seam):
// only the path adjacency crosses it.
TEST(EdgePath, CrossesASeamOfCoincidentVertices) {
  TriMesh m;
  add_strip(m, 3, 0.0);  // 0..2 bottom, 3..5 top; x = 0..2
  add_strip(m, 3, 2.0);  // 6..8 bottom, 9..11 top; x = 2..4 (6 and 9 on the seam)
  EXPECT_TRUE(edge_path(m.v, vertex_adjacency(m.v.size(), m.tris), 0, 8).empty());
  EXPECT_EQ(edge_path(m.v, path_adjacency(m.v, m.tris), 0, 8), (std::vector<int>{0, 1, 2, 6, 7}));
}

// A 4 × 4 grid; the contour through its corners is the grid's border.
TEST(JoinContour, ClosesALoopWhoseEndsSnapToOneVertex) {
  TriMesh m;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) m.v.push_back(Vec3(x, y, 0));
  for (int y = 0; y + 1 < 4; ++y)
    for (int x = 0; x + 1 < 4; ++x) {
      const int a = 4 * y + x;
      m.tris.push_back({a, a + 1, a + 5});
      m.tris.push_back({a, a + 5, a + 4});
    }
  const Adjacency adj = path_adjacency(m.v, m.tris);
  std::vector<int> border{0, 1, 2, 3, 7, 11, 15, 14, 13, 12, 8, 4};
  std::sort(border.begin(), border.end());
  // The first and last contour vertices snapped to the same mesh vertex (0), and repeats.
  for (const std::vector<int>& snapped :
       {std::vector<int>{0, 3, 15, 12, 0}, std::vector<int>{0, 0, 3, 15, 15, 12, 0, 0},
        std::vector<int>{0, 3, 15, 12}}) {
    std::vector<int> c = join_contour(m.v, adj, snapped);
    EXPECT_EQ(c.front(), 0);
    std::sort(c.begin(), c.end());
    EXPECT_EQ(c, border);
  }
  EXPECT_TRUE(join_contour(m.v, adj, {0, 3, 0}).empty());  // two distinct: no loop
  EXPECT_TRUE(join_contour(m.v, adj, {5, 5, 5}).empty());
}

}  // namespace
}  // namespace facectl::face
