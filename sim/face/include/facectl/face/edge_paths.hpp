// Shortest paths along a mesh's edges, and closed contours joined from them (fit-head
// joins an opening's snapped vertices this way where the new mesh is closed over it).
// Deterministic on meshes with coincident vertices: zero-length edges tie on distance, so
// ties go to the path of fewer edges, then to the lower vertex index.
#pragma once

#include <vector>

#include "facectl/face/mesh.hpp"

namespace facectl::face {

// The mesh's edges plus a zero-length link between vertices at exactly the same position
// (a seam or a duplicated vertex), so a path can cross from one copy to the other.
Adjacency path_adjacency(const Points& v, const std::vector<Tri>& tris);

// Vertices of a shortest path from a to b (a first, b excluded); among paths of equal
// length the one of fewest edges. Empty when a == b or b is unreachable.
std::vector<int> edge_path(const Points& v, const Adjacency& adj, int a, int b);

// A closed contour through `snapped` in order, joined by edge_path: the vertices of the
// loop, each once. Repeats of a vertex next to each other (also the last next to the first)
// count once. Empty when fewer than 3 distinct vertices remain or a part is unreachable.
std::vector<int> join_contour(const Points& v, const Adjacency& adj, std::vector<int> snapped);

}  // namespace facectl::face
