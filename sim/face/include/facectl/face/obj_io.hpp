// Wavefront OBJ reading (v and f records; polygons fan-triangulated) and writing.
#pragma once

#include <string>

#include "facectl/face/mesh.hpp"

namespace facectl::face {

// Reads `path`, scaling coordinates by `scale` (e.g. 0.01 for centimetres to metres).
// Throws InputError naming file:line on malformed records or out-of-range indices.
TriMesh read_obj(const std::string& path, double scale);
// Writes positions divided by `scale` (so read_obj(write_obj(m, s), s) round-trips).
void write_obj(const std::string& path, const TriMesh& mesh, double scale);

}  // namespace facectl::face
