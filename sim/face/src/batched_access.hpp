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
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

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

// The gathers into lanes and the stores back, on the three coordinate arrays of a Points
// and the inverse masses.
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
  FACECTL_INLINE void store(const Index& idx, const Lanes3& pos, int m) const {
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

}  // namespace facectl::face::batched
