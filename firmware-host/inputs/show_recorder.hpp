#pragma once

#include <array>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "control/command/face_layout.hpp"

namespace facectl {

// Records performed face poses as a show file that Show::load reads back
// (`facectl run --gamepad --record-show FILE`). Keyframes ease linearly, and a
// sample is left out when the keyframes around it reproduce it within a
// tolerance (0.006 degree, 0.01 mm, 0.001 contraction): holds and steady
// ramps cost two keyframes, while steps and turns keep theirs. A segment
// spans at most 1 s. Each keyframe lists the signals that differ from the
// neutral pose, in YAML units, clamped to each signal's domain (what the
// controller would accept). Not for the real-time thread: it allocates.
class ShowRecorder {
 public:
  ShowRecorder(const FaceLayout& layout, const std::array<double, kMaxFaceSignals>& neutral);

  // A pose performed at `t_s` seconds from the start; samples less than 1 ms
  // after the previous one are ignored.
  void add(double t_s, const std::array<double, kMaxFaceSignals>& pose);
  std::size_t keyframes() const { return frames_.size() + (window_.empty() ? 0 : 1); }
  std::string to_yaml(const std::string& name) const;
  // Writes to_yaml to `path`; throws std::runtime_error if it cannot.
  void write(const std::string& path, const std::string& name) const;

 private:
  struct Frame {
    double t = 0.0;
    std::array<double, kMaxFaceSignals> values{};
  };

  bool reproduces(const Frame& a, const Frame& c) const;

  const FaceLayout& layout_;
  std::array<double, kMaxFaceSignals> neutral_;
  std::array<double, kMaxFaceSignals> tolerance_{};
  std::vector<Frame> frames_;  // kept keyframes
  std::vector<Frame> window_;  // samples since the last kept one; its back is the tentative next
};

}  // namespace facectl
