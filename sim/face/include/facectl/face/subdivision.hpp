// Higher-resolution variants of a head: split the longest edges at their midpoints
// until the vertex count reaches a target. Each split edge adds one vertex, and a
// triangle splits into 2, 3 or 4 depending on how many of its edges were split, so
// the surface (and every landmark vertex index) is unchanged.
#pragma once

#include <cstddef>

#include "facectl/face/mesh.hpp"

namespace facectl::face {

// Also returns, for every new vertex, its two parent vertices (for carrying per-vertex
// data across). Deterministic: ties in edge length break by vertex index.
struct Refined {
  TriMesh mesh;
  std::vector<std::array<int, 2>> parents;  // size mesh.v.size(); {i,i} for original vertices
};
Refined refine_to_vertex_count(const TriMesh& base, std::size_t target_vertices);

}  // namespace facectl::face
