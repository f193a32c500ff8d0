// Finding the face on a head mesh that is not already a face looking along +z: a whole
// head (with the back of the skull and the neck), or a face looking along another
// direction about y. fit-head aligns bounding boxes, so it needs the face alone.
#pragma once

#include <cstddef>
#include <string>

#include "facectl/face/mesh.hpp"

namespace facectl::face {

struct FoundFace {
  TriMesh mesh;             // turned; a whole head also cut, without the vertices left unused
  double turn_degrees = 0;  // about y, +z toward +x, applied before any cut
  bool cut = false;         // a whole head, cut to the face
  double asymmetry = 0;     // mirror_asymmetry() of the turned head, before any cut
  double protrusion = 0;    // how far the nose stands out, over the width
  std::size_t kept_vertices = 0, head_vertices = 0;
};

// `m` turned by `degrees` about y, +z toward +x.
TriMesh turned_about_y(TriMesh m, double degrees);

// Turns `head` about y (y must be up) to look along +z. If that makes it a face
// (check_face_region), it is returned whole; otherwise (a whole head) only the region that
// `source_face` (a face looking along +z, e.g. the default mask) covers around its nose
// tip is kept, scaled by the two meshes' widths at the nose. The facing axis is the one about whose
// upright plane the head is mirror-symmetric; front and back by the nose, the frontmost
// point that stands out most from the surface beside it. Throws InputError naming `what`
// when no turn makes the head mirror-symmetric, nothing stands out in front like a nose,
// or what the cut keeps fails check_mesh_basics (too few vertices, say).
FoundFace find_face(const TriMesh& head, const TriMesh& source_face, const std::string& what);

}  // namespace facectl::face
