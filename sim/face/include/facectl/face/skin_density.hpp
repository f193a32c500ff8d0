// Skin stiffnesses carried between meshes of different vertex density (docs/FACE_MODEL.md,
// "Skin stiffness per unit area"). The skin's PBD sweep settles where the constraints'
// corrections cancel, each weighted by k/|∇C|². On a surface of edge length L an edge's
// stretch and a triangle's area keep their weight at any L (as a membrane's energy per
// unit area does), a hinge's bending weight falls as L² where the surface's does not, and
// an anchor's weight stays where it should fall with its vertex's share of the area. So
// stiffnesses tuned on one mesh hold on a denser or coarser one only once rescaled. Every
// weight scales alike when the whole head does (L² each), so only the density relative
// to the face's size matters.
#pragma once

#include "facectl/face/head_spec.hpp"
#include "facectl/face/mesh.hpp"

namespace facectl::face {

// Surface area over the vertices the triangles use (m² for a mesh in metres); 0 for none.
double mean_vertex_area(const TriMesh& m);

// The stiffnesses `k`, tuned on a skin whose mean vertex area is a0, for a skin of the same
// size whose mean vertex area is ratio·a0 (finite, > 0; else std::invalid_argument):
// relative to stretch and area, bending divided by ratio and the anchors multiplied by it;
// then all four scaled together so that the largest is k's largest (PBD needs each ≤ 1).
// For ratio < 1 and bending k's largest: stretch, area ×ratio, bending kept, anchor ×ratio².
// The skin's volume (one constraint over the whole skin, projected fully: a hard
// constraint), damping and the no-inversion floor are left as they are.
SkinStiffness stiffness_for_vertex_area(const SkinStiffness& k, double ratio);

}  // namespace facectl::face
