#include "facectl/face/convex_hull.hpp"

#include <cmath>
#include <limits>

#include "control/face/mandible.hpp"

namespace facectl::face {

ConvexHull convex_hull(const std::vector<Vec3>& pts) {
  ConvexHull h;
  h.points = pts;
  const int n = static_cast<int>(pts.size());
  Vec3 centroid = Vec3::Zero();
  for (const auto& p : pts) centroid += p;
  centroid /= std::max(1, n);
  double scale = 0;
  for (const auto& p : pts) scale = std::max(scale, (p - centroid).norm());
  const double eps = 1e-9 * std::max(scale, 1e-12);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        Vec3 nrm = (pts[j] - pts[i]).cross(pts[k] - pts[i]);
        double l = nrm.norm();
        if (l < eps * scale) continue;
        nrm /= l;
        int above = 0, below = 0;
        for (int m = 0; m < n; ++m) {
          double s = nrm.dot(pts[m] - pts[i]);
          above += s > eps;
          below += s < -eps;
        }
        if (above && below) continue;
        if (above) nrm = -nrm;  // make it outward
        Tri t = above ? Tri{i, k, j} : Tri{i, j, k};
        h.tris.push_back(t);
        double off = nrm.dot(pts[i]);
        bool dup = false;
        for (std::size_t q = 0; q < h.normals.size() && !dup; ++q)
          dup = h.normals[q].dot(nrm) > 1 - 1e-9 && std::abs(h.offsets[q] - off) < eps;
        if (!dup) {
          h.normals.push_back(nrm);
          h.offsets.push_back(off);
        }
      }
  h.box_min = h.box_max = n ? pts[0] : Vec3::Zero();
  for (const auto& p : pts) {
    h.box_min = h.box_min.cwiseMin(p);
    h.box_max = h.box_max.cwiseMax(p);
  }
  return h;
}

void transform_hull(const ConvexHull& rest, const RigidTransform& T, ConvexHull& out) {
  for (std::size_t i = 0; i < rest.points.size(); ++i) out.points[i] = T.apply(rest.points[i]);
  for (std::size_t i = 0; i < rest.normals.size(); ++i) {
    out.normals[i] = T.rotate(rest.normals[i]);
    out.offsets[i] = rest.offsets[i] + out.normals[i].dot(T.t);
  }
  out.box_min = out.box_max = out.points.empty() ? Vec3::Zero() : out.points[0];
  for (const auto& p : out.points) {
    out.box_min = out.box_min.cwiseMin(p);
    out.box_max = out.box_max.cwiseMax(p);
  }
}

bool inside(const ConvexHull& h, const Vec3& p, double margin) {
  if ((p.array() < h.box_min.array() - margin).any() ||
      (p.array() > h.box_max.array() + margin).any())
    return false;  // broad phase
  for (std::size_t i = 0; i < h.normals.size(); ++i)
    if (h.normals[i].dot(p) > h.offsets[i] + margin) return false;
  return true;
}

double exit_distance(const ConvexHull& h, const Vec3& p, const Vec3& dir) {
  double t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < h.normals.size(); ++i) {
    double nd = h.normals[i].dot(dir);
    if (nd > 1e-12) t = std::min(t, (h.offsets[i] - h.normals[i].dot(p)) / nd);
  }
  return t;
}

}  // namespace facectl::face
