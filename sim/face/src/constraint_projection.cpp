// Gauss–Seidel projections of the constraint sets (thesis §3.2, errata applied), batched
// (batched_access.hpp). Each kernel is written once over an access type and compiled for
// the structure-of-arrays Points (muscles, tests) and for the padded skin workspace.
#include <cmath>

#include "batched_access.hpp"
#include "dihedral.hpp"
#include "facectl/face/constraints.hpp"

namespace facectl::face {
namespace {

using batched::for_each_batch;
using batched::Index;
using batched::kBatch;
using batched::Lanes;
using batched::Lanes3;
using batched::PackedAccess;
using batched::SoaAccess;

template <class Access>
FACECTL_INLINE inline void distance_batches(const DistanceConstraints& s, const Access& P) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib;
    alignas(32) Lanes3 pa, pb, da, db;  // positions, corrections
    alignas(32) Lanes wa, wb, k, rest;
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], k[j] = s.k[i], rest[j] = s.rest[i];
    }
    P.gather(ia, pa, wa);
    P.gather(ib, pb, wb);
    for (int j = 0; j < kBatch; ++j) {
      const double dx = pa[0][j] - pb[0][j], dy = pa[1][j] - pb[1][j], dz = pa[2][j] - pb[2][j];
      const double wsum = wa[j] + wb[j];
      const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
      const bool ok = (wsum != 0) & (len >= 1e-12);
      // λ = −s: move each end along n by its mass share of the violation (eq. 3.18–3.19).
      const double q = k[j] * (len - rest[j]) / (ok ? len * wsum : 1.0);
      const double f = ok ? q : 0.0;
      const double fa = wa[j] * f, fb = wb[j] * f;
      da[0][j] = -(fa * dx), da[1][j] = -(fa * dy), da[2][j] = -(fa * dz);
      db[0][j] = fb * dx, db[1][j] = fb * dy, db[2][j] = fb * dz;
    }
    P.scatter_add(ia, da, m);
    P.scatter_add(ib, db, m);
  });
}

template <class Access>
FACECTL_INLINE inline void bending_batches(const BendingConstraints& s, const Access& P) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib, ic, id;
    alignas(32) Lanes3 pa, pb, pc, pd;
    alignas(32) Lanes wa, wb, wc, wd, k, cr, sr;
    alignas(32) Lanes3 da, db, dc, dd;  // corrections
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], ic[j] = s.c[i], id[j] = s.d[i];
      k[j] = s.k[i], cr[j] = s.cos_rest[i], sr[j] = s.sin_rest[i];
    }
    P.gather(ia, pa, wa);
    P.gather(ib, pb, wb);
    P.gather(ic, pc, wc);
    P.gather(id, pd, wd);
    for (int j = 0; j < kBatch; ++j) {
      // e = pb − pa, u = pc − pa, v = pd − pa
      const double ex = pb[0][j] - pa[0][j], ey = pb[1][j] - pa[1][j], ez = pb[2][j] - pa[2][j];
      const double ux = pc[0][j] - pa[0][j], uy = pc[1][j] - pa[1][j], uz = pc[2][j] - pa[2][j];
      const double vx = pd[0][j] - pa[0][j], vy = pd[1][j] - pa[1][j], vz = pd[2][j] - pa[2][j];
      const Dihedral h = dihedral_terms(ex, ey, ez, ux, uy, uz, vx, vy, vz);
      const double sdel = h.sin * cr[j] - h.cos * sr[j];  // sin(φ − rest)
      const double cdel = h.cos * cr[j] + h.sin * sr[j];  // cos(φ − rest)
      // C = φ − rest, evaluated as 2·sin((φ − rest)/2) = sin Δ / cos(Δ/2): monotone on
      // (−π, π), equal to the angle error to third order, no trigonometry, and no
      // cancellation near 0 (past |Δ| = π/2 it is ±√(2(1 − cos Δ))).
      const bool near = cdel >= 0;
      const double sq = std::sqrt(near ? 0.5 * (1 + cdel) : 2 * (1 - cdel));
      const double num = near ? sdel : std::copysign(sq, sdel);
      // Exact gradient (Bridson et al. 2003): ∇c φ = −|e| n1/|n1|², ∇d φ = |e| n2/|n2|²,
      // ∇a φ = −(1−s1)∇c φ − (1−s2)∇d φ, ∇b φ = −s1 ∇c φ − s2 ∇d φ, where s1, s2 are the
      // wings' foot points on the edge. 1/|n1|² = |n2|²·r².
      const double r2 = h.r * h.r;
      const double gc = -h.le * h.N2 * r2, gd = h.le * h.N1 * r2;  // ∇c φ = gc·n1, ∇d φ = gd·n2
      const double s1 = (ux * ex + uy * ey + uz * ez) * h.invE;
      const double s2 = (vx * ex + vy * ey + vz * ez) * h.invE;
      const double a1 = -(1 - s1) * gc, a2 = -(1 - s2) * gd;  // ∇a φ = a1·n1 + a2·n2
      const double b1 = -s1 * gc, b2 = -s2 * gd;              // ∇b φ = b1·n1 + b2·n2
      const double denom = wa[j] * (a1 * a1 * h.N1 + a2 * a2 * h.N2 + 2 * a1 * a2 * h.D) +
                           wb[j] * (b1 * b1 * h.N1 + b2 * b2 * h.N2 + 2 * b1 * b2 * h.D) +
                           wc[j] * gc * gc * h.N1 + wd[j] * gd * gd * h.N2;
      // Degenerate pairs are skipped: f = 0.
      const bool ok = h.valid & (denom >= 1e-20);
      const double q = -k[j] * num / (ok ? (near ? sq : 1.0) * denom : 1.0);
      const double f = ok ? q : 0.0;
      const double fa1 = f * wa[j] * a1, fa2 = f * wa[j] * a2;
      const double fb1 = f * wb[j] * b1, fb2 = f * wb[j] * b2;
      const double fc = f * wc[j] * gc, fd = f * wd[j] * gd;
      // (Written out: a loop over x, y, z here would stop the vectoriser.)
      da[0][j] = fa1 * h.n1x + fa2 * h.n2x, db[0][j] = fb1 * h.n1x + fb2 * h.n2x;
      da[1][j] = fa1 * h.n1y + fa2 * h.n2y, db[1][j] = fb1 * h.n1y + fb2 * h.n2y;
      da[2][j] = fa1 * h.n1z + fa2 * h.n2z, db[2][j] = fb1 * h.n1z + fb2 * h.n2z;
      dc[0][j] = fc * h.n1x, dc[1][j] = fc * h.n1y, dc[2][j] = fc * h.n1z;
      dd[0][j] = fd * h.n2x, dd[1][j] = fd * h.n2y, dd[2][j] = fd * h.n2z;
    }
    P.scatter_add(ia, da, m);
    P.scatter_add(ib, db, m);
    P.scatter_add(ic, dc, m);
    P.scatter_add(id, dd, m);
  });
}

// Unsigned (ref == nullptr) or signed area; see project_signed().
template <class Access>
FACECTL_INLINE inline void area_batches(const AreaConstraints& s, const Access& P,
                                        const Points* ref, const std::vector<double>* rest_sign) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib, ic;
    alignas(32) Lanes3 pa, pb, pc, rn;
    alignas(32) Lanes wa, wb, wc, k, rest, rs;
    alignas(32) Lanes3 da, db, dc;  // corrections
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], ic[j] = s.c[i], k[j] = s.k[i], rest[j] = s.rest[i];
      if (ref) {
        rs[j] = (*rest_sign)[i];
        rn[0][j] = ref->x[ia[j]], rn[1][j] = ref->y[ia[j]], rn[2][j] = ref->z[ia[j]];
      } else {
        rs[j] = 0, rn[0][j] = rn[1][j] = rn[2][j] = 0;
      }
    }
    P.gather(ia, pa, wa);
    P.gather(ib, pb, wb);
    P.gather(ic, pc, wc);
    for (int j = 0; j < kBatch; ++j) {
      // e1 = pb − pa = (ax, ay, az), e2 = pc − pa = (bx, by, bz)
      const double ax = pb[0][j] - pa[0][j], ay = pb[1][j] - pa[1][j], az = pb[2][j] - pa[2][j];
      const double bx = pc[0][j] - pa[0][j], by = pc[1][j] - pa[1][j], bz = pc[2][j] - pa[2][j];
      const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
      const double len = std::sqrt(cx * cx + cy * cy + cz * cz);  // 2·area
      // rest_sign 0 (and the unsigned variant): the sides are not told apart.
      const double cr_ref = cx * rn[0][j] + cy * rn[1][j] + cz * rn[2][j];
      const double sign = (rs[j] != 0) & (cr_ref * rs[j] < -0.5 * len) ? -1.0 : 1.0;
      // With n̂ = (e1×e2)/len: g2 = ½ e2×n̂ and g3 = ½ n̂×e1 (g1 = −g2 − g3), written with
      // (a×b)×c = b(a·c) − a(b·c) as combinations of e1 and e2; |g2| = ½|e2|, |g3| = ½|e1|
      // and |g1| = ½|e2 − e1| because both edges lie in the plane ⟂ n̂.
      const double e11 = ax * ax + ay * ay + az * az, e22 = bx * bx + by * by + bz * bz;
      const double e12 = ax * bx + ay * by + az * bz;
      const double denom = 0.25 * (wa[j] * (e11 - 2 * e12 + e22) + wb[j] * e22 + wc[j] * e11);
      const bool ok = (len >= 1e-14) & (denom >= 1e-20);
      const double inv = 0.5 / (ok ? len : 1.0);
      const double g2a = e22 * inv, g2b = -e12 * inv;  // g2 = g2a·e1 + g2b·e2
      const double g3a = -e12 * inv, g3b = e11 * inv;  // g3 = g3a·e1 + g3b·e2
      const double g2x = g2a * ax + g2b * bx, g2y = g2a * ay + g2b * by, g2z = g2a * az + g2b * bz;
      const double g3x = g3a * ax + g3b * bx, g3y = g3a * ay + g3b * by, g3z = g3a * az + g3b * bz;
      // ∇(sign·A) = sign·g, so Δp = −k·(sign·A − A0)·sign·g/Σw|g|².
      const double q = -k[j] * (sign * 0.5 * len - rest[j]) * sign / (ok ? denom : 1.0);
      const double f = ok ? q : 0.0;
      const double fa = f * wa[j], fb = f * wb[j], fc = f * wc[j];
      da[0][j] = -(fa * (g2x + g3x)), da[1][j] = -(fa * (g2y + g3y)),
      da[2][j] = -(fa * (g2z + g3z));
      db[0][j] = fb * g2x, db[1][j] = fb * g2y, db[2][j] = fb * g2z;
      dc[0][j] = fc * g3x, dc[1][j] = fc * g3y, dc[2][j] = fc * g3z;
    }
    P.scatter_add(ia, da, m);
    P.scatter_add(ib, db, m);
    P.scatter_add(ic, dc, m);
  });
}

// One no-inversion constraint from e1 = pb − pa, e2 = pc − pa, its rest normal n and lower
// bound: the corrections of a, b and c (zero when satisfied). Shared by the batched sweep
// and the single-constraint projection, so both do the same arithmetic.
struct UprightStep {
  double ax, ay, az, bx, by, bz, cx, cy, cz;
  bool active;
};

FACECTL_INLINE inline UprightStep upright_step(double e1x, double e1y, double e1z, double e2x,
                                               double e2y, double e2z, double nx, double ny,
                                               double nz, double lo, double wa, double wb,
                                               double wc, double k) {
  const double cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
  const double C = cx * nx + cy * ny + cz * nz - lo;
  // (e1×e2)·n = e1·(e2×n) = e2·(n×e1): ∇b = e2×n, ∇c = n×e1, ∇a = −∇b − ∇c.
  const double gbx = e2y * nz - e2z * ny, gby = e2z * nx - e2x * nz, gbz = e2x * ny - e2y * nx;
  const double gcx = ny * e1z - nz * e1y, gcy = nz * e1x - nx * e1z, gcz = nx * e1y - ny * e1x;
  const double gax = -(gbx + gcx), gay = -(gby + gcy), gaz = -(gbz + gcz);
  const double denom = wa * (gax * gax + gay * gay + gaz * gaz) +
                       wb * (gbx * gbx + gby * gby + gbz * gbz) +
                       wc * (gcx * gcx + gcy * gcy + gcz * gcz);
  const bool active = (C < 0) & (denom >= 1e-30);  // unilateral: only when violated
  const double q = -k * C / (active ? denom : 1.0);
  const double f = active ? q : 0.0;
  const double fa = f * wa, fb = f * wb, fc = f * wc;
  return {fa * gax, fa * gay, fa * gaz, fb * gbx, fb * gby,
          fb * gbz, fc * gcx, fc * gcy, fc * gcz, active};
}

template <class Access>
FACECTL_INLINE inline void upright_batches(const OrientationConstraints& s, const Access& P) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib, ic;
    alignas(32) Lanes3 pa, pb, pc, n;
    alignas(32) Lanes wa, wb, wc, k, lo;
    alignas(32) Lanes3 da, db, dc;  // corrections
    alignas(32) Lanes act;          // 1 where violated
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], ic[j] = s.c[i], k[j] = s.k[i], lo[j] = s.min[i];
      n[0][j] = s.nx[i], n[1][j] = s.ny[i], n[2][j] = s.nz[i];
    }
    P.gather(ia, pa, wa);
    P.gather(ib, pb, wb);
    P.gather(ic, pc, wc);
    for (int j = 0; j < kBatch; ++j) {
      const UprightStep u =
          upright_step(pb[0][j] - pa[0][j], pb[1][j] - pa[1][j], pb[2][j] - pa[2][j],
                       pc[0][j] - pa[0][j], pc[1][j] - pa[1][j], pc[2][j] - pa[2][j], n[0][j],
                       n[1][j], n[2][j], lo[j], wa[j], wb[j], wc[j], k[j]);
      da[0][j] = u.ax, da[1][j] = u.ay, da[2][j] = u.az;
      db[0][j] = u.bx, db[1][j] = u.by, db[2][j] = u.bz;
      dc[0][j] = u.cx, dc[1][j] = u.cy, dc[2][j] = u.cz;
      act[j] = u.active ? 1.0 : 0.0;
    }
    // Unilateral: most constraints are satisfied and move nothing, so only the violated
    // ones are written back.
    P.scatter_add(ia, da, m, &act);
    P.scatter_add(ib, db, m, &act);
    P.scatter_add(ic, dc, m, &act);
  });
}

// The volume constraint over any position store `p` with per-particle inverse mass
// `w(i)`; `grad` is caller-owned scratch.
template <class P, class W>
void volume_step(const VolumeConstraint& v, P& p, const W& w, Points& grad) {
  if (v.k == 0) return;
  for (int i : v.verts) grad.set(i, Vec3::Zero());
  double vol = 0;
  for (const Tri& t : v.tris) {
    const Vec3 a = p.get(t[0]) - v.origin, b = p.get(t[1]) - v.origin, c = p.get(t[2]) - v.origin;
    vol += a.cross(b).dot(c);
    grad.add(t[0], b.cross(c));
    grad.add(t[1], c.cross(a));
    grad.add(t[2], a.cross(b));
  }
  double denom = 0;
  for (int i : v.verts) denom += w(i) * grad.get(i).squaredNorm();
  if (denom < 1e-30) return;
  const double f = -v.k * (vol - v.rest) / denom;
  for (int i : v.verts) p.add(i, f * w(i) * grad.get(i));
}

// PackedPoints seen as get/add of positions.
struct PackedPositions {
  PackedPoints& p;
  Vec3 get(std::size_t i) const { return p.get(i); }
  void add(std::size_t i, const Vec3& d) const {
    p.q[i].x += d.x();
    p.q[i].y += d.y();
    p.q[i].z += d.z();
  }
};

}  // namespace

FACECTL_VECTOR_CLONES void project(const DistanceConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  distance_batches(s, SoaAccess(p, w));
}
FACECTL_VECTOR_CLONES void project(const DistanceConstraints& s, PackedPoints& p) {
  distance_batches(s, PackedAccess(p));
}

FACECTL_VECTOR_CLONES void project(const BendingConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  bending_batches(s, SoaAccess(p, w));
}
FACECTL_VECTOR_CLONES void project(const BendingConstraints& s, PackedPoints& p) {
  bending_batches(s, PackedAccess(p));
}

FACECTL_VECTOR_CLONES void project(const AreaConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  area_batches(s, SoaAccess(p, w), nullptr, nullptr);
}
FACECTL_VECTOR_CLONES void project_signed(const AreaConstraints& s, Points& p,
                                          const std::vector<double>& w, const Points& ref_normal,
                                          const std::vector<double>& rest_sign) {
  area_batches(s, SoaAccess(p, w), &ref_normal, &rest_sign);
}
FACECTL_VECTOR_CLONES void project_signed(const AreaConstraints& s, PackedPoints& p,
                                          const Points& ref_normal,
                                          const std::vector<double>& rest_sign) {
  area_batches(s, PackedAccess(p), &ref_normal, &rest_sign);
}

FACECTL_VECTOR_CLONES void project(const OrientationConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  upright_batches(s, SoaAccess(p, w));
}
FACECTL_VECTOR_CLONES void project(const OrientationConstraints& s, PackedPoints& p) {
  upright_batches(s, PackedAccess(p));
}

bool project_one(const OrientationConstraints& s, std::size_t i, Points& p,
                 const std::vector<double>& w, double floor_scale, double target_scale) {
  if (orientation_value(s, i, p, floor_scale) >= 0) return false;
  const int a = s.a[i], b = s.b[i], c = s.c[i];
  const UprightStep u =
      upright_step(p.x[b] - p.x[a], p.y[b] - p.y[a], p.z[b] - p.z[a], p.x[c] - p.x[a],
                   p.y[c] - p.y[a], p.z[c] - p.z[a], s.nx[i], s.ny[i], s.nz[i],
                   target_scale * s.min[i], w[a], w[b], w[c], s.k[i]);
  if (!u.active) return false;
  p.add(a, Vec3(u.ax, u.ay, u.az));
  p.add(b, Vec3(u.bx, u.by, u.bz));
  p.add(c, Vec3(u.cx, u.cy, u.cz));
  return true;
}

void project(const VolumeConstraint& v, Points& p, const std::vector<double>& w, Points& grad) {
  volume_step(
      v, p, [&](int i) { return w[i]; }, grad);
}
void project(const VolumeConstraint& v, PackedPoints& p, Points& grad) {
  PackedPositions pos{p};
  volume_step(
      v, pos, [&](int i) { return p.q[i].w; }, grad);
}

void project(const Attachments& s, Points& p, const std::vector<double>& w, const Points& targets) {
  const std::size_t n = s.size();
  for (std::size_t j = 0; j < n; ++j) {
    const int i = s.particle[j];
    if (w[i] == 0) continue;
    const double k = s.k[j];
    p.x[i] += k * (targets.x[j] - p.x[i]);
    p.y[i] += k * (targets.y[j] - p.y[i]);
    p.z[i] += k * (targets.z[j] - p.z[i]);
  }
}
void project(const Attachments& s, PackedPoints& p, const Points& targets) {
  const std::size_t n = s.size();
  for (std::size_t j = 0; j < n; ++j) {
    Particle& q = p.q[s.particle[j]];
    if (q.w == 0) continue;
    const double k = s.k[j];
    q.x += k * (targets.x[j] - q.x);
    q.y += k * (targets.y[j] - q.y);
    q.z += k * (targets.z[j] - q.z);
  }
}

}  // namespace facectl::face
