#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace facectl {

// Histogram of durations with 1 µs bins up to 20 ms (plus an overflow bin).
// One thread records (the tick: a relaxed atomic increment, no lock), any
// thread may read percentiles while it runs.
class LatencyHistogram {
 public:
  static constexpr std::size_t kBins = 20000;

  void record(double seconds);
  void clear();

  std::uint64_t count() const { return count_.load(std::memory_order_relaxed); }
  // Percentile p in [0, 100], in seconds (upper edge of its bin).
  double percentile(double p) const;
  double max() const { return static_cast<double>(max_ns_.load(std::memory_order_relaxed)) * 1e-9; }
  double mean() const;

 private:
  std::array<std::atomic<std::uint32_t>, kBins + 1> bins_{};
  std::atomic<std::uint64_t> count_{0};
  std::atomic<std::uint64_t> max_ns_{0};
  std::atomic<std::uint64_t> sum_ns_{0};
};

}  // namespace facectl
