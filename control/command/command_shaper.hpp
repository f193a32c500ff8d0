#pragma once

#include <array>

#include "control/capacity.hpp"
#include "control/command/face_layout.hpp"

namespace facectl {

struct ShapingParams {
  double activation_time_constant_s = 0.020;    // muscle contraction rising
  double deactivation_time_constant_s = 0.050;  // muscle contraction falling
  double smoothing_time_constant_s = 0.015;     // rigid DOFs (mandible, eyes, neck)
  double neutral_ease_time_s = 0.5;             // blend to neutral when input is stale
};

// Step 3 of the tick: blends the sanitised input with the neutral pose (the
// input watchdog fades the input out when it goes stale), then applies
// first-order muscle activation dynamics and smoothing of the rigid DOFs.
// Uses the measured dt of each tick, so a late tick advances further.
class CommandShaper {
 public:
  CommandShaper(const FaceLayout& layout, const ShapingParams& params,
                const std::array<double, kMaxFaceSignals>& neutral);

  void reset(const std::array<double, kMaxFaceSignals>& pose);

  // `input_stale` selects the neutral pose as the blend target.
  const std::array<double, kMaxFaceSignals>& apply(const std::array<double, kMaxFaceSignals>& input,
                                                   bool input_stale, double dt);

  const std::array<double, kMaxFaceSignals>& values() const { return shaped_; }
  double neutral_weight() const { return neutral_weight_; }

 private:
  const FaceLayout& layout_;
  ShapingParams params_;
  std::array<double, kMaxFaceSignals> neutral_;
  std::array<double, kMaxFaceSignals> shaped_{};
  double neutral_weight_ = 0.0;
  // The gains for gains_dt_, worked out again only when dt changes: offline
  // ticks repeat their dt; the real-time loop's measured dt changes every
  // tick, where this costs one comparison more than before.
  double gains_dt_ = -1.0;
  double ease_step_ = 1.0, rise_ = 1.0, fall_ = 1.0, smooth_ = 1.0;
};

}  // namespace facectl
