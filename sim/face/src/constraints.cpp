#include "facectl/face/constraints.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

// On x86-64 the batched projections are also compiled for AVX2 (4 doubles a vector
// instead of SSE2's 2) and the loader picks the variant the CPU has (GCC target_clones).
// Both variants do the same IEEE double operations with no FMA contraction, so the bits
// do not depend on the variant or the machine.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(FACECTL_NO_VECTOR_CLONES)
#define FACECTL_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define FACECTL_VECTOR_CLONES
#endif
#define FACECTL_INLINE __attribute__((always_inline))

namespace facectl::face {
namespace {

// The signed dihedral angle's terms from e = pb − pa, u = pc − pa, v = pd − pa: the wing
// normals n1 = e×u and n2 = e×v, their squared lengths and dot product, |e|², |e| and
// 1/|e|², r = 1/(|n1||n2|), and cos φ = n̂1·n̂2, sin φ = (n̂1×n̂2)·ê = −(u·n2)|e|·r (because
// (e×u)×(e×v) = (e·(u×v))e). The projection and the rest measurement share it, so C is
// exactly 0 at rest.
struct Dihedral {
  double n1x, n1y, n1z, n2x, n2y, n2z, N1, N2, E, D, r, le, invE, cos, sin;
  bool valid;
};

FACECTL_INLINE inline Dihedral dihedral_terms(double ex, double ey, double ez, double ux, double uy,
                                              double uz, double vx, double vy, double vz) {
  Dihedral h;
  h.n1x = ey * uz - ez * uy, h.n1y = ez * ux - ex * uz, h.n1z = ex * uy - ey * ux;
  h.n2x = ey * vz - ez * vy, h.n2y = ez * vx - ex * vz, h.n2z = ex * vy - ey * vx;
  h.N1 = h.n1x * h.n1x + h.n1y * h.n1y + h.n1z * h.n1z;
  h.N2 = h.n2x * h.n2x + h.n2y * h.n2y + h.n2z * h.n2z;
  h.E = ex * ex + ey * ey + ez * ez;
  h.D = h.n1x * h.n2x + h.n1y * h.n2y + h.n1z * h.n2z;
  // Branch-free (the batched projection vectorises it): a degenerate pair (a zero-area
  // wing, a zero-length edge) computes with stand-in lengths and reports !valid.
  h.valid = (h.N1 >= 1e-28) & (h.N2 >= 1e-28) & (h.E >= 1e-20);
  const double N1 = h.valid ? h.N1 : 1.0, N2 = h.valid ? h.N2 : 1.0, E = h.valid ? h.E : 1.0;
  const double R = std::sqrt(N1 * N2);
  h.le = std::sqrt(E);
  const double q = 1 / (R * E);  // one division for 1/R and 1/E
  h.r = q * E;
  h.invE = q * R;
  h.cos = h.D * h.r;
  h.sin = -(ux * h.n2x + uy * h.n2y + uz * h.n2z) * h.le * h.r;
  return h;
}

// Batched Gauss–Seidel. A set ordered by order_in_runs() splits into runs of constraints
// that share no particle, so up to kBatch consecutive constraints of a run can be read,
// computed and written back as a group with exactly the result of projecting them one
// after another: none reads what another writes. The computing loop then has no memory
// dependence from one constraint to the next: it always runs kBatch lanes (the lanes past
// the batch recompute its first constraint and are never written back), branch-free, so
// the compiler turns it into vector code, and the core overlaps the sqrt/division chains
// instead of waiting on each. A set without runs is projected one at a time. Vector or
// scalar, each lane does the same IEEE operations, so the bits do not depend on it.
constexpr int kBatch = 8;

template <class Fn>
FACECTL_INLINE inline void for_each_batch(const std::vector<int>& runs, std::size_t n, Fn&& fn) {
  if (runs.empty()) {
    for (std::size_t i = 0; i < n; ++i) fn(i, 1);
    return;
  }
  std::size_t i = 0;
  for (int end : runs)
    while (i < static_cast<std::size_t>(end)) {
      const int m = static_cast<int>(std::min<std::size_t>(kBatch, end - i));
      fn(i, m);
      i += static_cast<std::size_t>(m);
    }
}

// The three coordinate arrays of a Points, for the batched kernels' gathers and scatters.
struct Coords {
  double* q[3];
  explicit Coords(Points& p) : q{p.x.data(), p.y.data(), p.z.data()} {}
};

// e[·][j] = p[to] − p[from].
FACECTL_INLINE inline void gather_edge(const Coords& P, int from, int to, double (&e)[3][kBatch],
                                       int j) {
  for (int c = 0; c < 3; ++c) e[c][j] = P.q[c][to] - P.q[c][from];
}

// p[idx[j]] += d[·][j] for the first m lanes.
FACECTL_INLINE inline void scatter_add(const Coords& P, const int (&idx)[kBatch],
                                       const double (&d)[3][kBatch], int m) {
  for (int j = 0; j < m; ++j)
    for (int c = 0; c < 3; ++c) P.q[c][idx[j]] += d[c][j];
}

// Morton (Z-order) key of a point in the box [lo, lo + span], 10 bits an axis.
std::uint32_t morton(const Vec3& q, const Vec3& lo, const Vec3& span) {
  std::uint32_t key = 0;
  std::uint32_t c[3];
  for (int a = 0; a < 3; ++a) {
    const double t = span[a] > 0 ? (q[a] - lo[a]) / span[a] : 0.0;
    c[a] = static_cast<std::uint32_t>(std::clamp(t, 0.0, 1.0) * 1023.0);
  }
  for (int bit = 9; bit >= 0; --bit)
    for (int a = 0; a < 3; ++a) key = (key << 1) | ((c[a] >> bit) & 1u);
  return key;
}

// Gauss–Seidel order in batches: constraints sorted along a Z-order curve through their
// rest centroids (neighbours in the order are neighbours on the surface, so a batch's
// particles are mostly in cache), then cut greedily into batches of up to kBatch that
// share no particle, each batch taking the first fitting constraints of the next
// kWindow still waiting. `perm[new] = old`; `runs` holds the batch ends. Deterministic:
// it depends only on the index lists and the rest positions.
std::vector<std::size_t> batch_order(const std::vector<const std::vector<int>*>& idx,
                                     const Points& rest, std::vector<int>& runs) {
  constexpr std::size_t kWindow = 64;
  const std::size_t n = idx[0]->size();
  std::vector<Vec3> centre(n, Vec3::Zero());
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto* v : idx) centre[i] += rest.get((*v)[i]);
    centre[i] /= static_cast<double>(idx.size());
    // The key uses |x|, the distance from the head's sagittal plane x = 0, so a constraint
    // and its mirror image sit side by side in the order (a left-first tie-break keeps it
    // deterministic): left and right are solved alike and the face stays symmetric.
    centre[i].x() = std::abs(centre[i].x());
    lo = lo.cwiseMin(centre[i]);
    hi = hi.cwiseMax(centre[i]);
  }
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    double side = 0;  // mean signed x, for the tie-break
    for (const auto* v : idx) side += rest.x[(*v)[i]];
    key[i] = (std::uint64_t{morton(centre[i], lo, hi - lo)} << 1) | (side < 0 ? 1u : 0u);
  }
  std::vector<std::size_t> waiting(n);
  for (std::size_t i = 0; i < n; ++i) waiting[i] = i;
  std::stable_sort(waiting.begin(), waiting.end(),
                   [&](std::size_t x, std::size_t y) { return key[x] < key[y]; });
  std::vector<std::size_t> perm;
  std::vector<int> busy(rest.size(), -1);  // batch that holds a particle
  runs.clear();
  std::size_t head = 0;  // waiting[head..] are not placed yet; placed ones are marked
  std::vector<char> placed(n, 0);
  while (perm.size() < n) {
    const int batch = static_cast<int>(runs.size());
    std::size_t taken = 0, seen = 0;
    for (std::size_t w = head; w < n && seen < kWindow && taken < kBatch; ++w) {
      const std::size_t c = waiting[w];
      if (placed[c]) continue;
      ++seen;
      bool free = true;
      for (const auto* v : idx) free = free && busy[(*v)[c]] != batch;
      if (!free) continue;
      for (const auto* v : idx) busy[(*v)[c]] = batch;
      placed[c] = 1;
      perm.push_back(c);
      ++taken;
    }
    while (head < n && placed[waiting[head]]) ++head;
    runs.push_back(static_cast<int>(perm.size()));
  }
  return perm;
}

template <class T>
void permute(std::vector<T>& v, const std::vector<std::size_t>& perm) {
  std::vector<T> out(v.size());
  for (std::size_t i = 0; i < perm.size(); ++i) out[i] = v[perm[i]];
  v.swap(out);
}

Dihedral dihedral(const Points& p, int a, int b, int c, int d) {
  const Vec3 pa = p.get(a), e = p.get(b) - pa, u = p.get(c) - pa, v = p.get(d) - pa;
  return dihedral_terms(e.x(), e.y(), e.z(), u.x(), u.y(), u.z(), v.x(), v.y(), v.z());
}

}  // namespace

void DistanceConstraints::add(int ia, int ib, double r, double stiffness) {
  runs.clear();  // the runs no longer cover the set
  a.push_back(ia);
  b.push_back(ib);
  rest.push_back(r);
  k.push_back(stiffness);
}
void BendingConstraints::add(int ia, int ib, int ic, int id, double r, double stiffness) {
  runs.clear();
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  d.push_back(id);
  rest.push_back(r);
  cos_rest.push_back(std::cos(r));
  sin_rest.push_back(std::sin(r));
  k.push_back(stiffness);
}
void BendingConstraints::add_at_rest(const Points& p, int ia, int ib, int ic, int id,
                                     double stiffness) {
  const Dihedral h = dihedral(p, ia, ib, ic, id);
  add(ia, ib, ic, id, h.valid ? std::atan2(h.sin, h.cos) : 0.0, stiffness);
  if (h.valid) {  // the measured pair itself, so C is exactly 0 at rest
    cos_rest.back() = h.cos;
    sin_rest.back() = h.sin;
  }
}
void AreaConstraints::add(int ia, int ib, int ic, double r, double stiffness) {
  runs.clear();
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  rest.push_back(r);
  k.push_back(stiffness);
}
void OrientationConstraints::add(int ia, int ib, int ic, const Vec3& unit_normal, double min_value,
                                 double stiffness) {
  runs.clear();
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  nx.push_back(unit_normal.x());
  ny.push_back(unit_normal.y());
  nz.push_back(unit_normal.z());
  min.push_back(min_value);
  k.push_back(stiffness);
}
void Attachments::add(int i, double stiffness) {
  particle.push_back(i);
  k.push_back(stiffness);
}

double distance_value(const DistanceConstraints& s, std::size_t i, const Points& p) {
  return (p.get(s.a[i]) - p.get(s.b[i])).norm() - s.rest[i];
}

double bending_angle(const Points& p, int a, int b, int c, int d) {
  const Dihedral h = dihedral(p, a, b, c, d);
  return h.valid ? std::atan2(h.sin, h.cos) : 0.0;
}

double area_value(const AreaConstraints& s, std::size_t i, const Points& p) {
  Vec3 p1 = p.get(s.a[i]);
  return 0.5 * (p.get(s.b[i]) - p1).cross(p.get(s.c[i]) - p1).norm() - s.rest[i];
}

double volume_of(const VolumeConstraint& v, const Points& p) {
  double sum = 0;
  for (const Tri& t : v.tris)
    sum += (p.get(t[0]) - v.origin).cross(p.get(t[1]) - v.origin).dot(p.get(t[2]) - v.origin);
  return sum;
}

FACECTL_VECTOR_CLONES void project(const DistanceConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  const Coords P(p);
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    int ia[kBatch], ib[kBatch];
    double e[3][kBatch], wa[kBatch], wb[kBatch], k[kBatch], rest[kBatch];  // e = pa − pb
    double da[3][kBatch], db[3][kBatch];                                   // corrections
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], k[j] = s.k[i], rest[j] = s.rest[i];
      wa[j] = w[ia[j]], wb[j] = w[ib[j]];
      gather_edge(P, ib[j], ia[j], e, j);
    }
    for (int j = 0; j < kBatch; ++j) {
      const double dx = e[0][j], dy = e[1][j], dz = e[2][j];
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
    scatter_add(P, ia, da, m);
    scatter_add(P, ib, db, m);
  });
}

FACECTL_VECTOR_CLONES void project(const BendingConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  const Coords P(p);
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    int ia[kBatch], ib[kBatch], ic[kBatch], id[kBatch];
    double e[3][kBatch], u[3][kBatch], v[3][kBatch];  // e = pb − pa, u = pc − pa, v = pd − pa
    double wa[kBatch], wb[kBatch], wc[kBatch], wd[kBatch], k[kBatch], cr[kBatch], sr[kBatch];
    double da[3][kBatch], db[3][kBatch], dc[3][kBatch], dd[3][kBatch];  // corrections
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], ic[j] = s.c[i], id[j] = s.d[i];
      k[j] = s.k[i], cr[j] = s.cos_rest[i], sr[j] = s.sin_rest[i];
      wa[j] = w[ia[j]], wb[j] = w[ib[j]], wc[j] = w[ic[j]], wd[j] = w[id[j]];
      gather_edge(P, ia[j], ib[j], e, j);
      gather_edge(P, ia[j], ic[j], u, j);
      gather_edge(P, ia[j], id[j], v, j);
    }
    for (int j = 0; j < kBatch; ++j) {
      const Dihedral h = dihedral_terms(e[0][j], e[1][j], e[2][j], u[0][j], u[1][j], u[2][j],
                                        v[0][j], v[1][j], v[2][j]);
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
      const double s1 = (u[0][j] * e[0][j] + u[1][j] * e[1][j] + u[2][j] * e[2][j]) * h.invE;
      const double s2 = (v[0][j] * e[0][j] + v[1][j] * e[1][j] + v[2][j] * e[2][j]) * h.invE;
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
    scatter_add(P, ia, da, m);
    scatter_add(P, ib, db, m);
    scatter_add(P, ic, dc, m);
    scatter_add(P, id, dd, m);
  });
}

namespace {

template <bool kSigned>
FACECTL_VECTOR_CLONES void project_area(const AreaConstraints& s, Points& p,
                                        const std::vector<double>& w, const Points* ref,
                                        const std::vector<double>* rest_sign) {
  const Coords P(p);
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    int ia[kBatch], ib[kBatch], ic[kBatch];
    double e1[3][kBatch], e2[3][kBatch], rn[3][kBatch];
    double wa[kBatch], wb[kBatch], wc[kBatch], k[kBatch], rest[kBatch], rs[kBatch];
    double da[3][kBatch], db[3][kBatch], dc[3][kBatch];  // corrections
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], ic[j] = s.c[i], k[j] = s.k[i], rest[j] = s.rest[i];
      wa[j] = w[ia[j]], wb[j] = w[ib[j]], wc[j] = w[ic[j]];
      gather_edge(P, ia[j], ib[j], e1, j);
      gather_edge(P, ia[j], ic[j], e2, j);
      if constexpr (kSigned) {
        rs[j] = (*rest_sign)[i];
        rn[0][j] = ref->x[ia[j]], rn[1][j] = ref->y[ia[j]], rn[2][j] = ref->z[ia[j]];
      } else {
        rs[j] = 0, rn[0][j] = rn[1][j] = rn[2][j] = 0;
      }
    }
    for (int j = 0; j < kBatch; ++j) {
      const double ax = e1[0][j], ay = e1[1][j], az = e1[2][j];
      const double bx = e2[0][j], by = e2[1][j], bz = e2[2][j];
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
    scatter_add(P, ia, da, m);
    scatter_add(P, ib, db, m);
    scatter_add(P, ic, dc, m);
  });
}

}  // namespace

void project(const AreaConstraints& s, Points& p, const std::vector<double>& w) {
  project_area<false>(s, p, w, nullptr, nullptr);
}

void project_signed(const AreaConstraints& s, Points& p, const std::vector<double>& w,
                    const Points& ref_normal, const std::vector<double>& rest_sign) {
  project_area<true>(s, p, w, &ref_normal, &rest_sign);
}

namespace {

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

}  // namespace

FACECTL_VECTOR_CLONES void project(const OrientationConstraints& s, Points& p,
                                   const std::vector<double>& w) {
  const Coords P(p);
  for_each_batch(s.runs, s.size(), [&](std::size_t i0, int m) FACECTL_INLINE {
    int ia[kBatch], ib[kBatch], ic[kBatch];
    double e1[3][kBatch], e2[3][kBatch], n[3][kBatch];
    double wa[kBatch], wb[kBatch], wc[kBatch], k[kBatch], lo[kBatch];
    double da[3][kBatch], db[3][kBatch], dc[3][kBatch];  // corrections
    double act[kBatch];                                  // 1 where violated
    for (int j = 0; j < kBatch; ++j) {
      const std::size_t i = i0 + (j < m ? j : 0);
      ia[j] = s.a[i], ib[j] = s.b[i], ic[j] = s.c[i], k[j] = s.k[i], lo[j] = s.min[i];
      n[0][j] = s.nx[i], n[1][j] = s.ny[i], n[2][j] = s.nz[i];
      wa[j] = w[ia[j]], wb[j] = w[ib[j]], wc[j] = w[ic[j]];
      gather_edge(P, ia[j], ib[j], e1, j);
      gather_edge(P, ia[j], ic[j], e2, j);
    }
    for (int j = 0; j < kBatch; ++j) {
      const UprightStep u =
          upright_step(e1[0][j], e1[1][j], e1[2][j], e2[0][j], e2[1][j], e2[2][j], n[0][j], n[1][j],
                       n[2][j], lo[j], wa[j], wb[j], wc[j], k[j]);
      da[0][j] = u.ax, da[1][j] = u.ay, da[2][j] = u.az;
      db[0][j] = u.bx, db[1][j] = u.by, db[2][j] = u.bz;
      dc[0][j] = u.cx, dc[1][j] = u.cy, dc[2][j] = u.cz;
      act[j] = u.active ? 1.0 : 0.0;
    }
    // Unilateral: most constraints are satisfied and move nothing, so only the violated
    // ones are written back.
    for (int j = 0; j < m; ++j)
      if (act[j] != 0)
        for (int c = 0; c < 3; ++c) {
          P.q[c][ia[j]] += da[c][j];
          P.q[c][ib[j]] += db[c][j];
          P.q[c][ic[j]] += dc[c][j];
        }
  });
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

double orientation_value(const OrientationConstraints& s, std::size_t i, const Points& p,
                         double floor_scale) {
  const int a = s.a[i], b = s.b[i], c = s.c[i];
  const double e1x = p.x[b] - p.x[a], e1y = p.y[b] - p.y[a], e1z = p.z[b] - p.z[a];
  const double e2x = p.x[c] - p.x[a], e2y = p.y[c] - p.y[a], e2z = p.z[c] - p.z[a];
  return (e1y * e2z - e1z * e2y) * s.nx[i] + (e1z * e2x - e1x * e2z) * s.ny[i] +
         (e1x * e2y - e1y * e2x) * s.nz[i] - floor_scale * s.min[i];
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

namespace {
template <class T>
void append_to(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}
}  // namespace

void append(DistanceConstraints& to, const DistanceConstraints& from) {
  to.runs.clear();
  for (auto [t, f] : {std::pair{&to.a, &from.a}, {&to.b, &from.b}}) append_to(*t, *f);
  for (auto [t, f] : {std::pair{&to.rest, &from.rest}, {&to.k, &from.k}}) append_to(*t, *f);
}

void append(BendingConstraints& to, const BendingConstraints& from) {
  to.runs.clear();
  for (auto [t, f] :
       {std::pair{&to.a, &from.a}, {&to.b, &from.b}, {&to.c, &from.c}, {&to.d, &from.d}})
    append_to(*t, *f);
  for (auto [t, f] : {std::pair{&to.rest, &from.rest},
                      {&to.cos_rest, &from.cos_rest},
                      {&to.sin_rest, &from.sin_rest},
                      {&to.k, &from.k}})
    append_to(*t, *f);
}

void order_in_runs(DistanceConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b}, rest, s.runs);
  for (auto* v : {&s.a, &s.b}) permute(*v, perm);
  for (auto* v : {&s.rest, &s.k}) permute(*v, perm);
}

void order_in_runs(BendingConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b, &s.c, &s.d}, rest, s.runs);
  for (auto* v : {&s.a, &s.b, &s.c, &s.d}) permute(*v, perm);
  for (auto* v : {&s.rest, &s.cos_rest, &s.sin_rest, &s.k}) permute(*v, perm);
}

void order_in_runs(AreaConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b, &s.c}, rest, s.runs);
  for (auto* v : {&s.a, &s.b, &s.c}) permute(*v, perm);
  for (auto* v : {&s.rest, &s.k}) permute(*v, perm);
}

void order_in_runs(OrientationConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b, &s.c}, rest, s.runs);
  for (auto* v : {&s.a, &s.b, &s.c}) permute(*v, perm);
  for (auto* v : {&s.nx, &s.ny, &s.nz, &s.min, &s.k}) permute(*v, perm);
}

void add_edge_distances(DistanceConstraints& s, const Points& p, const std::vector<Tri>& tris,
                        double k) {
  for (Edge e : unique_edges(tris)) s.add(e.a, e.b, (p.get(e.a) - p.get(e.b)).norm(), k);
  order_in_runs(s, p);
}

void add_bending(BendingConstraints& s, const Points& p, const std::vector<Tri>& tris, double k) {
  for (EdgePair e : interior_edge_pairs(tris)) s.add_at_rest(p, e.a, e.b, e.c, e.d, k);
  order_in_runs(s, p);
}

void add_areas(AreaConstraints& s, const Points& p, const std::vector<Tri>& tris, double k) {
  for (const Tri& t : tris) {
    s.add(t[0], t[1], t[2], 0, k);
    s.rest.back() = area_value(s, s.size() - 1, p);
  }
  order_in_runs(s, p);
}

void add_orientations(OrientationConstraints& s, const Points& p, const std::vector<Tri>& tris,
                      double min_fraction, double k) {
  for (const Tri& t : tris) {
    const Vec3 cr = (p.get(t[1]) - p.get(t[0])).cross(p.get(t[2]) - p.get(t[0]));
    const double len = cr.norm();
    if (len > 0) s.add(t[0], t[1], t[2], cr / len, min_fraction * len, k);
  }
  order_in_runs(s, p);
}

VolumeConstraint make_volume(const Points& p, const std::vector<Tri>& tris, const Vec3& origin,
                             double k) {
  VolumeConstraint v;
  v.tris = tris;
  for (const Tri& t : tris) v.verts.insert(v.verts.end(), t.begin(), t.end());
  std::sort(v.verts.begin(), v.verts.end());
  v.verts.erase(std::unique(v.verts.begin(), v.verts.end()), v.verts.end());
  v.origin = origin;
  v.k = k;
  v.rest = volume_of(v, p);
  return v;
}

}  // namespace facectl::face
