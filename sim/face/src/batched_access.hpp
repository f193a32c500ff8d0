// Batched Gauss–Seidel machinery shared by the constraint projections (internal header).
// A set ordered by order_in_runs() splits into runs of constraints that share no particle,
// so up to kBatch consecutive constraints of a run can be read, computed and written back
// as a group with exactly the result of projecting them one after another: none reads what
// another writes. The computing loop then has no memory dependence from one constraint to
// the next: it always runs kBatch lanes (the lanes past the batch recompute its first
// constraint and are never written back), branch-free, so the compiler turns it into vector
// code, and the core overlaps the sqrt/division chains instead of waiting on each. A set
// without runs is projected one at a time. Vector or scalar, each lane does the same IEEE
// operations, so the bits do not depend on it.
//
// The gathers and scatters go through an access type: SoaAccess reads the three arrays of a
// Points one scalar at a time; PackedAccess reads a PackedPoints slot with one 32-byte load
// and transposes four slots into x, y, z lanes (and back for the scatter). Both move the
// same values, so a projection gives the same bits through either.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

#include "facectl/face/packed_points.hpp"
#include "facectl/face/points.hpp"

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

namespace facectl::face::batched {

constexpr int kBatch = 8;

// Lanes of a batch: one value per constraint, aligned for whole-vector loads and stores.
using Lanes = double[kBatch];
using Lanes3 = double[3][kBatch];  // x, y, z lanes
using Index = int[kBatch];

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

// The three coordinate arrays of a Points and the inverse masses.
struct SoaAccess {
  double* q[3];
  const double* w;
  SoaAccess(Points& p, const std::vector<double>& inv_mass)
      : q{p.x.data(), p.y.data(), p.z.data()}, w(inv_mass.data()) {}

  FACECTL_INLINE void gather(const Index& idx, Lanes3& pos, Lanes& wl) const {
    for (int j = 0; j < kBatch; ++j) {
      for (int c = 0; c < 3; ++c) pos[c][j] = q[c][idx[j]];
      wl[j] = w[idx[j]];
    }
  }
  // p[idx[j]] = pos[·][j] for the first m lanes.
  FACECTL_INLINE void store(const Index& idx, const Lanes3& pos, const Lanes&, int m) const {
    for (int j = 0; j < m; ++j)
      for (int c = 0; c < 3; ++c) q[c][idx[j]] = pos[c][j];
  }
  // p[idx[j]] += d[·][j] for the first m lanes whose `on` is nonzero.
  FACECTL_INLINE void scatter_add(const Index& idx, const Lanes3& d, int m,
                                  const Lanes* on = nullptr) const {
    for (int j = 0; j < m; ++j)
      if (!on || (*on)[j] != 0)
        for (int c = 0; c < 3; ++c) q[c][idx[j]] += d[c][j];
  }
};

// GCC vector extensions: lowered to AVX2 in that clone and to SSE2 pairs otherwise. The
// helpers below are always inlined, so the 32-byte vector ABI note (-Wpsabi) is moot.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
using v4d = double __attribute__((vector_size(32)));
using v4l = long long __attribute__((vector_size(32)));

// 4×4 transpose: rows (x, y, z, w) of four particles ↔ columns of four lanes.
FACECTL_INLINE inline void transpose4(v4d& r0, v4d& r1, v4d& r2, v4d& r3) {
  const v4d t0 = __builtin_shuffle(r0, r1, v4l{0, 4, 2, 6});
  const v4d t1 = __builtin_shuffle(r0, r1, v4l{1, 5, 3, 7});
  const v4d t2 = __builtin_shuffle(r2, r3, v4l{0, 4, 2, 6});
  const v4d t3 = __builtin_shuffle(r2, r3, v4l{1, 5, 3, 7});
  r0 = __builtin_shuffle(t0, t2, v4l{0, 1, 4, 5});
  r1 = __builtin_shuffle(t1, t3, v4l{0, 1, 4, 5});
  r2 = __builtin_shuffle(t0, t2, v4l{2, 3, 6, 7});
  r3 = __builtin_shuffle(t1, t3, v4l{2, 3, 6, 7});
}

FACECTL_INLINE inline v4d load4(const double* p) {
  v4d v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
FACECTL_INLINE inline void store4(double* p, const v4d& v) {
  std::memcpy(p, &v, sizeof v);
}

// The padded slots of a PackedPoints; the inverse mass rides in the fourth lane.
struct PackedAccess {
  Particle* q;
  explicit PackedAccess(PackedPoints& p) : q(p.q.data()) {}

  FACECTL_INLINE void gather(const Index& idx, Lanes3& pos, Lanes& wl) const {
    for (int h = 0; h < kBatch; h += 4) {
      v4d r[4];
      for (int l = 0; l < 4; ++l) r[l] = load4(&q[idx[h + l]].x);
      transpose4(r[0], r[1], r[2], r[3]);
      for (int c = 0; c < 3; ++c) store4(&pos[c][h], r[c]);
      store4(&wl[h], r[3]);
    }
  }
  // Writes whole slots (x, y, z and the inverse mass as gathered) for the first m lanes.
  FACECTL_INLINE void store(const Index& idx, const Lanes3& pos, const Lanes& wl, int m) const {
    for (int h = 0; h < m; h += 4) {
      v4d r[4] = {load4(&pos[0][h]), load4(&pos[1][h]), load4(&pos[2][h]), load4(&wl[h])};
      transpose4(r[0], r[1], r[2], r[3]);
      for (int l = 0; l < 4 && h + l < m; ++l) store4(&q[idx[h + l]].x, r[l]);
    }
  }
  // Adds (dx, dy, dz, 0) to the slot: the inverse mass lane is left as it was.
  FACECTL_INLINE void scatter_add(const Index& idx, const Lanes3& d, int m,
                                  const Lanes* on = nullptr) const {
    for (int h = 0; h < m; h += 4) {
      v4d r[4] = {load4(&d[0][h]), load4(&d[1][h]), load4(&d[2][h]), v4d{0, 0, 0, 0}};
      transpose4(r[0], r[1], r[2], r[3]);
      for (int l = 0; l < 4 && h + l < m; ++l)
        if (!on || (*on)[h + l] != 0) {
          double* s = &q[idx[h + l]].x;
          store4(s, load4(s) + r[l]);
        }
    }
  }
};

#pragma GCC diagnostic pop

}  // namespace facectl::face::batched
