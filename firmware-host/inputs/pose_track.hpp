#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "control/capacity.hpp"

namespace facectl {

// Full face poses at increasing times, played like a show: evaluate(t)
// interpolates linearly between samples and holds the ends. What every
// recorded input (FAP, capture, lip sync) becomes before it is played. Keeps
// the layout's signals only (a default-head pose is 41 doubles, not 96).
class PoseTrack {
 public:
  explicit PoseTrack(std::size_t signal_count = 0) : signal_count_(signal_count) {}

  // Times must increase strictly; the caller's parser has checked its file.
  void add(double t, const std::array<double, kMaxFaceSignals>& values);
  void reserve(std::size_t n);

  bool empty() const { return times_.empty(); }
  std::size_t size() const { return times_.size(); }
  double start() const { return times_.front(); }
  double duration() const { return times_.back(); }
  double time(std::size_t k) const { return times_[k]; }
  std::span<const double> pose(std::size_t k) const {
    return {values_.data() + k * signal_count_, signal_count_};
  }
  void evaluate(double t, std::array<double, kMaxFaceSignals>& out) const;

 private:
  std::size_t signal_count_;
  std::vector<double> times_;
  std::vector<double> values_;  // signal_count_ per sample
};

}  // namespace facectl
