#include "facectl/face/surface_point.hpp"

#include <cmath>

namespace facectl::face {

double ray_triangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c,
                    double& u, double& v) {
  const Vec3 e1 = b - a, e2 = c - a, pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (std::abs(det) < 1e-18) return -1;
  const double inv = 1 / det;
  const Vec3 tv = o - a;
  u = tv.dot(pv) * inv;
  if (u < -1e-9 || u > 1 + 1e-9) return -1;
  const Vec3 qv = tv.cross(e1);
  v = d.dot(qv) * inv;
  if (v < -1e-9 || u + v > 1 + 1e-9) return -1;
  return e2.dot(qv) * inv;
}

}  // namespace facectl::face
