// A mesh renumbered by its geometry alone, so that what is computed on it does not depend
// on how a file happened to number its vertices and order its faces (fit-head: the same
// head exported twice in different orders fits to the same folder).
#pragma once

#include <vector>

#include "facectl/face/mesh.hpp"

namespace facectl::face {

struct CanonicalMesh {
  TriMesh mesh;               // vertices sorted by position, triangles renumbered and sorted
  std::vector<int> original;  // original[k]: the input's index of canonical vertex k
};

// Vertices in lexicographic order of (x, y, z); coincident vertices keep their input
// order. Each triangle is renumbered, rotated to start at its lowest vertex (the winding
// stays) and the triangles are sorted.
CanonicalMesh canonical_mesh(const TriMesh& m);

// Canonical vertex indices back to the input's numbering, in place.
void to_original_indices(const CanonicalMesh& c, std::vector<int>& vertices);

}  // namespace facectl::face
