// The fused edge sweep (an edge's stretch projected with its bending pair) is exactly
// Gauss–Seidel in its documented order.
#include <gtest/gtest.h>

#include <random>

#include "facectl/face/constraints.hpp"

namespace facectl::face {
namespace {

// A bumpy n × n grid of triangles, in metres, with some pinned (w = 0) and heavy particles.
struct Sheet {
  TriMesh mesh;
  std::vector<double> w;
};

Sheet bumpy_sheet(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> bump(-0.002, 0.002);
  Sheet s;
  for (int r = 0; r <= n; ++r)
    for (int c = 0; c <= n; ++c) s.mesh.v.push_back(Vec3(0.005 * c, 0.005 * r, bump(rng)));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const int i = r * (n + 1) + c;
      s.mesh.tris.push_back({i, i + 1, i + n + 2});
      s.mesh.tris.push_back({i, i + n + 2, i + n + 1});
    }
  for (std::size_t i = 0; i < s.mesh.v.size(); ++i)
    s.w.push_back(i % 17 == 0 ? 0.0 : 1.0 + static_cast<double>(i % 3));
  return s;
}

void shake(Points& p, std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-0.003, 0.003);
  for (std::size_t i = 0; i < p.size(); ++i) p.add(i, Vec3(d(rng), d(rng), d(rng)));
}

// The fused edge sweep is Gauss–Seidel in the interleaved order: each pair's edge stretch,
// then its bending, constraint after constraint.
TEST(FusedEdgeSweep, IsStretchThenBendingConstraintByConstraint) {
  std::mt19937 rng(11);
  const Sheet s = bumpy_sheet(10, rng);
  const Points& rest = s.mesh.v;
  DistanceConstraints edges;
  BendingConstraints bending;
  add_edge_distances(edges, rest, s.mesh.tris, 0.4);
  add_bending(bending, rest, s.mesh.tris, 0.9);
  const std::size_t all_edges = edges.size();
  const PairStretch pair = split_pair_stretch(edges, bending, rest);
  ASSERT_EQ(pair.k.size(), bending.size());
  EXPECT_EQ(edges.size() + bending.size(), all_edges);  // border edges stay; none is lost
  for (double k : pair.k) EXPECT_EQ(k, 0.4);            // every pair carries its edge

  Points p = rest;
  shake(p, rng);
  Points ref = p;
  project_with_stretch(bending, pair, p, s.w);
  for (std::size_t i = 0; i < bending.size(); ++i) {
    DistanceConstraints one_edge;
    one_edge.add(bending.a[i], bending.b[i], pair.rest[i], pair.k[i]);
    BendingConstraints one_pair;
    one_pair.add(bending.a[i], bending.b[i], bending.c[i], bending.d[i], bending.rest[i],
                 bending.k[i]);
    one_pair.cos_rest.back() = bending.cos_rest[i];
    one_pair.sin_rest.back() = bending.sin_rest[i];
    project(one_edge, ref, s.w);
    project(one_pair, ref, s.w);
  }
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p.get(i), ref.get(i)) << i;
}

}  // namespace
}  // namespace facectl::face
