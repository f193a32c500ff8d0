// Gauss–Seidel projections of the constraint sets (thesis §3.2, errata applied), batched
// (batched_access.hpp).
#include <cmath>
#include <cstring>

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
using batched::SoaAccess;

// One particle's position in one lane of a batch.
struct P3 {
  double x, y, z;
};
FACECTL_INLINE inline P3 lane(const Lanes3& p, int j) {
  return {p[0][j], p[1][j], p[2][j]};
}
FACECTL_INLINE inline void set_lane(Lanes3& p, int j, const P3& v) {
  p[0][j] = v.x, p[1][j] = v.y, p[2][j] = v.z;
}

// The lane steps below move their particles in place: p ← p + Δp, the same IEEE
// operations as adding the correction in memory, so the sweep stays exactly Gauss–Seidel
// and a fused kernel (two constraints on the same particles, one after the other in the
// lane) gives the bits of the two projected in sequence.

// Distance: C = |a − b| − rest.
FACECTL_INLINE inline void stretch_step(P3& a, P3& b, double wa, double wb, double k, double rest) {
  const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  const double wsum = wa + wb;
  const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
  const bool ok = (wsum != 0) & (len >= 1e-12);
  // λ = −s: move each end along n by its mass share of the violation (eq. 3.18–3.19).
  const double q = k * (len - rest) / (ok ? len * wsum : 1.0);
  const double f = ok ? q : 0.0;
  const double fa = wa * f, fb = wb * f;
  a.x += -(fa * dx), a.y += -(fa * dy), a.z += -(fa * dz);
  b.x += fb * dx, b.y += fb * dy, b.z += fb * dz;
}

// Bending of the pair (a, b, c) and (a, b, d) about edge ab: C = φ − rest. The arithmetic
// runs in single precision (twice the lanes a vector, and faster square roots and
// divisions) on the edge vectors scaled by 2^10, so that a skin or muscle edge of about
// a millimetre is about 1 and nothing near the thresholds leaves float's normal range;
// the positions and the sums p + Δp stay double. Exact powers of two keep the scaling
// exact, and every lane does the same IEEE operations, so the bits are still the same
// scalar, SSE2 or AVX2. Thresholds in scaled units: a wing with 2·area < about 1e−4 mm²
// or an edge shorter than about 1 µm is degenerate and skipped.
FACECTL_INLINE inline void bending_step(P3& a, P3& b, P3& c, P3& d, double wa_, double wb_,
                                        double wc_, double wd_, double k_, double cr_, double sr_) {
  constexpr double kUp = 1024.0, kDown = 1.0 / 1024.0;
  using F = float;
  const F ex = F((b.x - a.x) * kUp), ey = F((b.y - a.y) * kUp), ez = F((b.z - a.z) * kUp);
  const F ux = F((c.x - a.x) * kUp), uy = F((c.y - a.y) * kUp), uz = F((c.z - a.z) * kUp);
  const F vx = F((d.x - a.x) * kUp), vy = F((d.y - a.y) * kUp), vz = F((d.z - a.z) * kUp);
  const F wa = F(wa_), wb = F(wb_), wc = F(wc_), wd = F(wd_), k = F(k_), cr = F(cr_), sr = F(sr_);
  const DihedralT<F> h = dihedral_terms<F>(ex, ey, ez, ux, uy, uz, vx, vy, vz, 1e-8f, 1e-6f);
  const F sdel = h.sin * cr - h.cos * sr;  // sin(φ − rest)
  const F cdel = h.cos * cr + h.sin * sr;  // cos(φ − rest)
  // C = φ − rest, evaluated as 2·sin((φ − rest)/2) = sin Δ / cos(Δ/2): monotone on
  // (−π, π), equal to the angle error to third order, no trigonometry, and no
  // cancellation near 0 (past |Δ| = π/2 it is ±√(2(1 − cos Δ))).
  const bool near = cdel >= 0;
  const F sq = std::sqrt(near ? F(0.5) * (1 + cdel) : 2 * (1 - cdel));
  const F num = near ? sdel : std::copysign(sq, sdel);
  // Exact gradient (Bridson et al. 2003): ∇c φ = −|e| n1/|n1|², ∇d φ = |e| n2/|n2|²,
  // ∇a φ = −(1−s1)∇c φ − (1−s2)∇d φ, ∇b φ = −s1 ∇c φ − s2 ∇d φ, where s1, s2 are the
  // wings' foot points on the edge. 1/|n1|² = |n2|²·r².
  const F r2 = h.r * h.r;
  const F gc = -h.le * h.N2 * r2, gd = h.le * h.N1 * r2;  // ∇c φ = gc·n1, ∇d φ = gd·n2
  const F s1 = (ux * ex + uy * ey + uz * ez) * h.invE;
  const F s2 = (vx * ex + vy * ey + vz * ez) * h.invE;
  const F a1 = -(1 - s1) * gc, a2 = -(1 - s2) * gd;  // ∇a φ = a1·n1 + a2·n2
  const F b1 = -s1 * gc, b2 = -s2 * gd;              // ∇b φ = b1·n1 + b2·n2
  const F denom = wa * (a1 * a1 * h.N1 + a2 * a2 * h.N2 + 2 * a1 * a2 * h.D) +
                  wb * (b1 * b1 * h.N1 + b2 * b2 * h.N2 + 2 * b1 * b2 * h.D) + wc * gc * gc * h.N1 +
                  wd * gd * gd * h.N2;
  // Degenerate pairs are skipped: f = 0.
  const bool ok = h.valid & (denom >= 1e-20f);
  const F q = -k * num / (ok ? (near ? sq : F(1)) * denom : F(1));
  const F f = ok ? q : F(0);
  const F fa1 = f * wa * a1, fa2 = f * wa * a2;
  const F fb1 = f * wb * b1, fb2 = f * wb * b2;
  const F fc = f * wc * gc, fd = f * wd * gd;
  // (Written out: a loop over x, y, z here would stop the vectoriser.)
  a.x += double(fa1 * h.n1x + fa2 * h.n2x) * kDown,
      b.x += double(fb1 * h.n1x + fb2 * h.n2x) * kDown;
  a.y += double(fa1 * h.n1y + fa2 * h.n2y) * kDown,
      b.y += double(fb1 * h.n1y + fb2 * h.n2y) * kDown;
  a.z += double(fa1 * h.n1z + fa2 * h.n2z) * kDown,
      b.z += double(fb1 * h.n1z + fb2 * h.n2z) * kDown;
  c.x += double(fc * h.n1x) * kDown, c.y += double(fc * h.n1y) * kDown;
  c.z += double(fc * h.n1z) * kDown;
  d.x += double(fd * h.n2x) * kDown, d.y += double(fd * h.n2y) * kDown;
  d.z += double(fd * h.n2z) * kDown;
}

// Area of (a, b, c).
FACECTL_INLINE inline void area_step(P3& a, P3& b, P3& c, double wa, double wb, double wc, double k,
                                     double rest) {
  // e1 = pb − pa = (ax, ay, az), e2 = pc − pa = (bx, by, bz)
  const double ax = b.x - a.x, ay = b.y - a.y, az = b.z - a.z;
  const double bx = c.x - a.x, by = c.y - a.y, bz = c.z - a.z;
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  const double len = std::sqrt(cx * cx + cy * cy + cz * cz);  // 2·area
  // With n̂ = (e1×e2)/len: g2 = ½ e2×n̂ and g3 = ½ n̂×e1 (g1 = −g2 − g3), written with
  // (a×b)×c = b(a·c) − a(b·c) as combinations of e1 and e2; |g2| = ½|e2|, |g3| = ½|e1|
  // and |g1| = ½|e2 − e1| because both edges lie in the plane ⟂ n̂.
  const double e11 = ax * ax + ay * ay + az * az, e22 = bx * bx + by * by + bz * bz;
  const double e12 = ax * bx + ay * by + az * bz;
  const double denom = 0.25 * (wa * (e11 - 2 * e12 + e22) + wb * e22 + wc * e11);
  const bool ok = (len >= 1e-14) & (denom >= 1e-20);
  const double inv = 0.5 / (ok ? len : 1.0);
  const double g2a = e22 * inv, g2b = -e12 * inv;  // g2 = g2a·e1 + g2b·e2
  const double g3a = -e12 * inv, g3b = e11 * inv;  // g3 = g3a·e1 + g3b·e2
  const double g2x = g2a * ax + g2b * bx, g2y = g2a * ay + g2b * by, g2z = g2a * az + g2b * bz;
  const double g3x = g3a * ax + g3b * bx, g3y = g3a * ay + g3b * by, g3z = g3a * az + g3b * bz;
  // Δp = −k·(A − A0)·g/Σw|g|².
  const double q = -k * (0.5 * len - rest) / (ok ? denom : 1.0);
  const double f = ok ? q : 0.0;
  const double fa = f * wa, fb = f * wb, fc = f * wc;
  a.x += -(fa * (g2x + g3x)), a.y += -(fa * (g2y + g3y)), a.z += -(fa * (g2z + g3z));
  b.x += fb * g2x, b.y += fb * g2y, b.z += fb * g2z;
  c.x += fc * g3x, c.y += fc * g3y, c.z += fc * g3z;
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

// out[j] = v[i0 + j], the lanes past a batch of m repeating its first constraint. A full
// batch (most of them) is one contiguous copy.
template <class T>
FACECTL_INLINE inline void lanes_of(const std::vector<T>& v, std::size_t i0, int m,
                                    T (&out)[kBatch]) {
  if (m == kBatch) {
    std::memcpy(out, v.data() + i0, sizeof out);
    return;
  }
  for (int j = 0; j < kBatch; ++j) out[j] = v[i0 + static_cast<std::size_t>(j < m ? j : 0)];
}

FACECTL_INLINE inline void distance_batches(const DistanceConstraints& s, const SoaAccess& P) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib;
    alignas(32) Lanes3 pa, pb;
    alignas(32) Lanes wa, wb, k, rest;
    lanes_of(s.a, i0, m, ia), lanes_of(s.b, i0, m, ib);
    lanes_of(s.k, i0, m, k), lanes_of(s.rest, i0, m, rest);
    P.gather(ia, pa, wa);
    P.gather(ib, pb, wb);
    for (int j = 0; j < kBatch; ++j) {
      P3 a = lane(pa, j), b = lane(pb, j);
      stretch_step(a, b, wa[j], wb[j], k[j], rest[j]);
      set_lane(pa, j, a), set_lane(pb, j, b);
    }
    P.store(ia, pa, m);
    P.store(ib, pb, m);
  });
}

// Bending pairs; with `stretch`, each pair's shared edge ab is first stretched (rest and
// stiffness stretch->rest[i], stretch->k[i]), in the same lane.
FACECTL_INLINE inline void bending_batches(const BendingConstraints& s, const PairStretch* stretch,
                                           const SoaAccess& P) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib, ic, id;
    alignas(32) Lanes3 pa, pb, pc, pd;
    alignas(32) Lanes wa, wb, wc, wd, k, cr, sr, ks, rs;
    lanes_of(s.a, i0, m, ia), lanes_of(s.b, i0, m, ib);
    lanes_of(s.c, i0, m, ic), lanes_of(s.d, i0, m, id);
    lanes_of(s.k, i0, m, k), lanes_of(s.cos_rest, i0, m, cr), lanes_of(s.sin_rest, i0, m, sr);
    if (stretch) lanes_of(stretch->k, i0, m, ks), lanes_of(stretch->rest, i0, m, rs);
    P.gather(ia, pa, wa);
    P.gather(ib, pb, wb);
    P.gather(ic, pc, wc);
    P.gather(id, pd, wd);
    for (int j = 0; j < kBatch; ++j) {
      P3 a = lane(pa, j), b = lane(pb, j), c = lane(pc, j), d = lane(pd, j);
      if (stretch) stretch_step(a, b, wa[j], wb[j], ks[j], rs[j]);
      bending_step(a, b, c, d, wa[j], wb[j], wc[j], wd[j], k[j], cr[j], sr[j]);
      set_lane(pa, j, a), set_lane(pb, j, b), set_lane(pc, j, c), set_lane(pd, j, d);
    }
    P.store(ia, pa, m);
    P.store(ib, pb, m);
    P.store(ic, pc, m);
    P.store(id, pd, m);
  });
}

FACECTL_INLINE inline void area_batches(const AreaConstraints& s, const SoaAccess& P) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib, ic;
    alignas(32) Lanes3 pa, pb, pc;
    alignas(32) Lanes wa, wb, wc, k, rest;
    lanes_of(s.a, i0, m, ia), lanes_of(s.b, i0, m, ib), lanes_of(s.c, i0, m, ic);
    lanes_of(s.k, i0, m, k), lanes_of(s.rest, i0, m, rest);
    P.gather(ia, pa, wa);
    P.gather(ib, pb, wb);
    P.gather(ic, pc, wc);
    for (int j = 0; j < kBatch; ++j) {
      P3 a = lane(pa, j), b = lane(pb, j), c = lane(pc, j);
      area_step(a, b, c, wa[j], wb[j], wc[j], k[j], rest[j]);
      set_lane(pa, j, a), set_lane(pb, j, b), set_lane(pc, j, c);
    }
    P.store(ia, pa, m);
    P.store(ib, pb, m);
    P.store(ic, pc, m);
  });
}

FACECTL_INLINE inline void upright_batches(const OrientationConstraints& s, const SoaAccess& P) {
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    alignas(32) Index ia, ib, ic;
    alignas(32) Lanes3 pa, pb, pc, n;
    alignas(32) Lanes wa, wb, wc, k, lo;
    alignas(32) Lanes3 da, db, dc;  // corrections
    alignas(32) Lanes act;          // 1 where violated
    lanes_of(s.a, i0, m, ia), lanes_of(s.b, i0, m, ib), lanes_of(s.c, i0, m, ic);
    lanes_of(s.k, i0, m, k), lanes_of(s.min, i0, m, lo);
    lanes_of(s.nx, i0, m, n[0]), lanes_of(s.ny, i0, m, n[1]), lanes_of(s.nz, i0, m, n[2]);
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

}  // namespace

FACECTL_VECTOR_CLONES void project(const DistanceConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  distance_batches(s, SoaAccess(p, w));
}

FACECTL_VECTOR_CLONES void project(const BendingConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  bending_batches(s, nullptr, SoaAccess(p, w));
}
FACECTL_VECTOR_CLONES void project_with_stretch(const BendingConstraints& s,
                                                const PairStretch& stretch, Points& p,
                                                const std::vector<double>& w) {
  bending_batches(s, &stretch, SoaAccess(p, w));
}

FACECTL_VECTOR_CLONES void project(const AreaConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  area_batches(s, SoaAccess(p, w));
}
FACECTL_VECTOR_CLONES void project(const OrientationConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  upright_batches(s, SoaAccess(p, w));
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
  for (int i : v.verts) denom += w[i] * grad.get(i).squaredNorm();
  if (denom < 1e-30) return;
  const double f = -v.k * (vol - v.rest) / denom;
  for (int i : v.verts) p.add(i, f * w[i] * grad.get(i));
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

}  // namespace facectl::face
