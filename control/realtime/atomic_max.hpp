#pragma once

#include <atomic>
#include <cstdint>

namespace facectl {

// Raises `a` to `v` if `v` is larger, lock-free (a running maximum that
// several threads may update and any thread may read).
inline void atomic_max(std::atomic<std::uint64_t>& a, std::uint64_t v) {
  std::uint64_t cur = a.load(std::memory_order_relaxed);
  while (v > cur && !a.compare_exchange_weak(cur, v, std::memory_order_relaxed)) {
  }
}

}  // namespace facectl
