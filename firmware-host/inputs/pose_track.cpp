#include "firmware-host/inputs/pose_track.hpp"

#include <algorithm>
#include <stdexcept>

namespace facectl {

void PoseTrack::add(double t, const std::array<double, kMaxFaceSignals>& values) {
  if (!times_.empty() && !(t > times_.back())) {
    throw std::logic_error("PoseTrack::add: times must increase");
  }
  times_.push_back(t);
  values_.insert(values_.end(), values.begin(), values.begin() + static_cast<long>(signal_count_));
}

void PoseTrack::reserve(std::size_t n) {
  times_.reserve(n);
  values_.reserve(n * signal_count_);
}

void PoseTrack::evaluate(double t, std::array<double, kMaxFaceSignals>& out) const {
  if (t <= times_.front() || t >= times_.back()) {
    const auto p = pose(t <= times_.front() ? 0 : times_.size() - 1);
    std::copy(p.begin(), p.end(), out.begin());
    return;
  }
  const auto next = std::upper_bound(times_.begin(), times_.end(), t);
  const auto k = static_cast<std::size_t>(next - times_.begin());
  const double w = (t - times_[k - 1]) / (times_[k] - times_[k - 1]);
  const auto a = pose(k - 1);
  const auto b = pose(k);
  for (std::size_t i = 0; i < signal_count_; ++i) out[i] = a[i] + w * (b[i] - a[i]);
}

}  // namespace facectl
