// The skin anchors' targets: support point plus the rest offset in the support's frame
// (SurfacePoint::smooth_frame on a muscle, SurfacePoint::frame on the skull), written out
// on plain doubles with one reciprocal per normalisation (the divisions dominated). A
// degenerate support takes SurfacePoint's own fallbacks.
#include "skin_anchors.hpp"

#include <cmath>

namespace facectl::face {
namespace {

// Anchor i's target and normal. `Bone` is a template argument so that each list's loop has
// no branch on the support kind (a mixed loop mispredicted it about once in five).
template <bool Bone>
inline void anchor_target(const FaceModel& m, FaceData& d, const Points& src, int i) {
  const Points& vn = d.muscle_normals;
  const SurfacePoint& sp = m.anchor_support[i];
  const int i0 = sp.i0, i1 = sp.i1, i2 = sp.i2;
  const double t0 = sp.t0, t1 = sp.t1, t2 = sp.t2;
  double ex = src.x[i1] - src.x[i0], ey = src.y[i1] - src.y[i0], ez = src.z[i1] - src.z[i0];
  double nx, ny, nz;
  bool ok;
  if constexpr (Bone) {  // normal of the triangle, first edge
    const double ux = src.x[i2] - src.x[i0], uy = src.y[i2] - src.y[i0], uz = src.z[i2] - src.z[i0];
    nx = ey * uz - ez * uy, ny = ez * ux - ex * uz, nz = ex * uy - ey * ux;
    const double en = std::sqrt(ex * ex + ey * ey + ez * ez);
    const double nn = std::sqrt(nx * nx + ny * ny + nz * nz);
    ok = en != 0 && nn != 0;
    if (ok) {
      const double ie = 1 / en, in = 1 / nn;
      ex *= ie, ey *= ie, ez *= ie, nx *= in, ny *= in, nz *= in;
    }
  } else {  // interpolated vertex normal, first edge made tangent
    nx = t0 * vn.x[i0] + t1 * vn.x[i1] + t2 * vn.x[i2];
    ny = t0 * vn.y[i0] + t1 * vn.y[i1] + t2 * vn.y[i2];
    nz = t0 * vn.z[i0] + t1 * vn.z[i1] + t2 * vn.z[i2];
    const double nn = std::sqrt(nx * nx + ny * ny + nz * nz);
    ok = nn != 0;
    if (ok) {
      const double in = 1 / nn;
      nx *= in, ny *= in, nz *= in;
      const double ne = nx * ex + ny * ey + nz * ez;
      ex -= nx * ne, ey -= ny * ne, ez -= nz * ne;
      const double en = std::sqrt(ex * ex + ey * ey + ez * ez);
      ok = en != 0;
      const double ie = 1 / (ok ? en : 1.0);
      ex *= ie, ey *= ie, ez *= ie;
    }
  }
  const Vec3 o = sp.position(src);
  if (!ok) {  // rare: SurfacePoint's fallbacks
    const Mat3 F = Bone ? sp.frame(src) : sp.smooth_frame(src, vn);
    d.anchor_targets.set(i, o + F * m.anchor_local.get(i));
    return;
  }
  // Columns (ê, n̂ × ê, n̂).
  const double bx = ny * ez - nz * ey, by = nz * ex - nx * ez, bz = nx * ey - ny * ex;
  const double lx = m.anchor_local.x[i], ly = m.anchor_local.y[i], lz = m.anchor_local.z[i];
  d.anchor_targets.x[i] = o.x() + (ex * lx + bx * ly + nx * lz);
  d.anchor_targets.y[i] = o.y() + (ey * lx + by * ly + ny * lz);
  d.anchor_targets.z[i] = o.z() + (ez * lx + bz * ly + nz * lz);
}

}  // namespace

void update_moving_anchor_targets(const FaceModel& m, FaceData& d) {
  vertex_normals(d.muscles, m.muscle_tops, d.muscle_normals);
  for (int i : m.anchors_on_muscles) anchor_target<false>(m, d, d.muscles, i);
  for (int i : m.anchors_on_jaw) anchor_target<true>(m, d, d.skull, i);
}

void set_fixed_anchor_targets(const FaceModel& m, FaceData& d) {
  for (int i : m.anchors_on_fixed_skull) anchor_target<true>(m, d, d.skull, i);
}

}  // namespace facectl::face
