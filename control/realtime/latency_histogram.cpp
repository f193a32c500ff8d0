#include "control/realtime/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace facectl {

void LatencyHistogram::record(double seconds) {
  const double ns = std::max(0.0, seconds * 1e9);
  const auto ns_int = static_cast<std::uint64_t>(ns);
  const std::size_t bin = std::min<std::size_t>(ns_int / 1000, kBins);
  bins_[bin].fetch_add(1, std::memory_order_relaxed);
  count_.fetch_add(1, std::memory_order_relaxed);
  sum_ns_.fetch_add(ns_int, std::memory_order_relaxed);
  if (ns_int > max_ns_.load(std::memory_order_relaxed)) {
    max_ns_.store(ns_int, std::memory_order_relaxed);
  }
}

void LatencyHistogram::clear() {
  for (auto& b : bins_) b.store(0, std::memory_order_relaxed);
  count_.store(0, std::memory_order_relaxed);
  max_ns_.store(0, std::memory_order_relaxed);
  sum_ns_.store(0, std::memory_order_relaxed);
}

double LatencyHistogram::percentile(double p) const {
  const std::uint64_t n = count();
  if (n == 0) return 0.0;
  const auto rank = static_cast<std::uint64_t>(
      std::ceil(std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(n)));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i <= kBins; ++i) {
    seen += bins_[i].load(std::memory_order_relaxed);
    if (seen >= std::max<std::uint64_t>(rank, 1)) {
      return i == kBins ? max() : static_cast<double>(i + 1) * 1e-6;
    }
  }
  return max();
}

double LatencyHistogram::mean() const {
  const std::uint64_t n = count();
  return n == 0 ? 0.0
                : static_cast<double>(sum_ns_.load(std::memory_order_relaxed)) * 1e-9 /
                      static_cast<double>(n);
}

}  // namespace facectl
