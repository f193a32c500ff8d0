// Convex hull of a small point set (the teeth, thesis) as triangles plus
// outward face planes, found by brute force over point triples: O(n⁴) but exact and
// tiny for the few dozen points of a dental arch. Queries: inside test and the exit
// point of a ray from an inside point.
#pragma once

#include <vector>

#include "facectl/face/mesh.hpp"

namespace facectl::face {

struct ConvexHull {
  std::vector<Vec3> points;     // the input points
  std::vector<Tri> tris;        // hull faces, outward winding (for rendering)
  std::vector<Vec3> normals;    // one per distinct face plane, unit, outward
  std::vector<double> offsets;  // plane: normals[i]·x = offsets[i]
  Vec3 box_min, box_max;        // axis-aligned bounding box
};

ConvexHull convex_hull(const std::vector<Vec3>& points);
// Re-evaluates planes and box after a rigid motion of the hull (no allocation).
struct RigidTransform;
void transform_hull(const ConvexHull& rest, const RigidTransform& T, ConvexHull& out);
bool inside(const ConvexHull& h, const Vec3& p, double margin = 0);
// For p inside, the distance along unit `dir` to the hull boundary.
double exit_distance(const ConvexHull& h, const Vec3& p, const Vec3& dir);

}  // namespace facectl::face
