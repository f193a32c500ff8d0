// Skin stiffnesses carried between meshes of different vertex density (docs/FACE_MODEL.md,
// "Skin stiffness per unit area"). The skin's PBD sweep settles where the constraints'
// corrections cancel, each weighted by k/|∇C|². On a surface of edge length L an edge's
// stretch and a triangle's area keep their weight at any L (as a membrane's energy per
// unit area does), a hinge's bending weight falls as L² where the surface's does not, and
// an anchor's weight stays where it should fall with its vertex's share of the area. So
// stiffnesses tuned on one mesh hold on a denser or coarser one only once rescaled.
#pragma once

#include "facectl/face/head_spec.hpp"
#include "facectl/face/mesh.hpp"

namespace facectl::face {

// Surface area over the vertices the triangles use (m² for a mesh in metres); 0 for none.
double mean_vertex_area(const TriMesh& m);

// The stiffnesses `k`, tuned on a skin whose mean vertex area is a0, for a skin whose
// mean vertex area is ratio·a0 (ratio > 0): relative to stretch and area, bending scaled by
// 1/ratio and the anchors by ratio. PBD keeps every k ≤ 1, so the larger side is held and
// the others lowered: with s = min(1, ratio), stretch·s, area·s, bending·s/ratio and
// anchor·ratio·s, all four divided by the largest if that passes 1 (a coarse skin's
// anchors). Volume, damping and the no-inversion floor are not per element and stay.
SkinStiffness stiffness_for_vertex_area(const SkinStiffness& k, double ratio);

}  // namespace facectl::face
