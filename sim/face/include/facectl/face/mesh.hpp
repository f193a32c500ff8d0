// Triangle mesh: SoA vertex positions plus an index list, and the topology queries
// the model builder needs (edges, edge-adjacent triangle pairs, boundary loops).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "facectl/face/points.hpp"

namespace facectl::face {

using Tri = std::array<int, 3>;

struct TriMesh {
  Points v;
  std::vector<Tri> tris;
};

struct Edge {
  int a, b;  // a < b
};

// Two triangles sharing edge (a,b): opposite vertices c (in the first) and d (in the second).
struct EdgePair {
  int a, b, c, d;
};

// 1 for each vertex some triangle uses, 0 for a loose one (what OBJ exporters leave).
std::vector<char> used_vertices(const TriMesh& m);
std::vector<Edge> unique_edges(const std::vector<Tri>& tris);
std::vector<EdgePair> interior_edge_pairs(const std::vector<Tri>& tris);
// Boundary loops as ordered vertex lists (edges used by exactly one triangle).
std::vector<std::vector<int>> boundary_loops(const std::vector<Tri>& tris);
// Area-weighted vertex normals, written into `out` (resized to v.size()).
void vertex_normals(const Points& v, const std::vector<Tri>& tris, Points& out);
Vec3 triangle_normal(const Points& v, const Tri& t);  // unit, counter-clockwise
// Vertex-to-vertex adjacency in CSR form, for Dijkstra over mesh edges.
struct Adjacency {
  std::vector<int> start;  // size n+1
  std::vector<int> nbr;
};
Adjacency vertex_adjacency(std::size_t n, const std::vector<Tri>& tris);
// The same from an edge list (each edge once).
Adjacency adjacency_from_edges(std::size_t n, const std::vector<Edge>& edges);
// Geodesic distance along mesh edges from the seed set (Dijkstra); unreachable = +inf.
std::vector<double> edge_geodesic(const Points& v, const Adjacency& adj,
                                  const std::vector<int>& seeds);

}  // namespace facectl::face
