// Surface point (thesis): a triangle of some particle array plus constant
// barycentric coordinates, so it rides on the triangle while the triangle deforms.
// `layer` says which array: the skull (rigid bones) or the muscle particles.
#pragma once

#include <cstdint>

#include "facectl/face/points.hpp"

namespace facectl::face {

enum class Layer : std::uint8_t { kSkull = 0, kMuscle = 1 };

struct SurfacePoint {
  Layer layer = Layer::kSkull;
  int i0 = 0, i1 = 0, i2 = 0;
  double t0 = 1, t1 = 0, t2 = 0;  // t0 + t1 + t2 = 1, each ≥ 0

  Vec3 position(const Points& p) const { return t0 * p.get(i0) + t1 * p.get(i1) + t2 * p.get(i2); }
  // Unit normal of the underlying triangle (counter-clockwise winding).
  Vec3 normal(const Points& p) const {
    Vec3 n = (p.get(i1) - p.get(i0)).cross(p.get(i2) - p.get(i0));
    double l = n.norm();
    return l > 0 ? Vec3(n / l) : Vec3(0, 0, 1);
  }
  // Frame whose normal interpolates per-vertex normals `vn` (smooth, and stable when the
  // triangle itself becomes thin) and whose first axis is the first edge made tangent.
  Mat3 smooth_frame(const Points& p, const Points& vn) const {
    Vec3 n = t0 * vn.get(i0) + t1 * vn.get(i1) + t2 * vn.get(i2);
    const double nn = n.norm();
    if (nn == 0) return frame(p);
    n /= nn;
    Vec3 e = p.get(i1) - p.get(i0);
    e -= n * n.dot(e);
    const double en = e.norm();
    if (en == 0) return frame(p);
    return columns(e / en, n);
  }
  // Orthonormal frame (edge, normal × edge, normal) of the triangle, as columns.
  Mat3 frame(const Points& p) const {
    const Vec3 e = p.get(i1) - p.get(i0);
    const Vec3 n = e.cross(p.get(i2) - p.get(i0));
    const double en = e.norm(), nn = n.norm();
    if (en == 0 || nn == 0) return Mat3::Identity();
    return columns(e / en, n / nn);
  }

 private:
  static Mat3 columns(const Vec3& unit_e, const Vec3& unit_n) {
    Mat3 F;
    F.col(0) = unit_e;
    F.col(1) = unit_n.cross(unit_e);
    F.col(2) = unit_n;
    return F;
  }
};

// Ray/triangle intersection (Möller–Trumbore). Returns t along `dir` or a negative value
// when there is no hit; writes the barycentric coordinates of the hit.
double ray_triangle(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b,
                    const Vec3& c, double& u, double& v);

}  // namespace facectl::face
