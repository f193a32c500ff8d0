// Padded positions (x, y, z, inverse mass), one 32-byte slot a particle: the skin solver's
// scratch copy of a Points. A batched projection reads a particle with one vector load and
// writes its correction back with one vector add, where the structure-of-arrays state
// needs three scattered scalar accesses each way. The model's state stays a Points;
// step_face() packs it once before the skin iterations and unpacks it after, like a
// workspace beside the canonical data (docs/FACE_MODEL.md, "Packed skin workspace").
#pragma once

#include <cstddef>
#include <vector>

#include "facectl/face/points.hpp"

namespace facectl::face {

struct alignas(32) Particle {
  double x, y, z, w;  // w: inverse mass, read by the projections, never written
};

struct PackedPoints {
  std::vector<Particle> q;
  std::size_t size() const { return q.size(); }
  Vec3 get(std::size_t i) const { return {q[i].x, q[i].y, q[i].z}; }
};

// out ← (p, w). Allocates only when out is smaller than p.
void pack(const Points& p, const std::vector<double>& w, PackedPoints& out);
// out ← positions of `in` (out already sized; no allocation).
void unpack(const PackedPoints& in, Points& out);

}  // namespace facectl::face
