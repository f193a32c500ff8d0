#include "control/command/command_shaper.hpp"

#include <algorithm>
#include <cmath>

namespace facectl {
namespace {

// Exact discretisation of a first-order lag for a step of dt.
double lag_gain(double dt, double time_constant) {
  return time_constant <= 0.0 ? 1.0 : 1.0 - std::exp(-dt / time_constant);
}

}  // namespace

CommandShaper::CommandShaper(const FaceLayout& layout, const ShapingParams& params,
                             const std::array<double, kMaxFaceSignals>& neutral)
    : layout_(layout), params_(params), neutral_(neutral), shaped_(neutral) {}

void CommandShaper::reset(const std::array<double, kMaxFaceSignals>& pose) {
  shaped_ = pose;
  neutral_weight_ = 0.0;
}

const std::array<double, kMaxFaceSignals>& CommandShaper::apply(
    const std::array<double, kMaxFaceSignals>& input, bool input_stale, double dt) {
  if (dt != gains_dt_) {
    gains_dt_ = dt;
    ease_step_ = params_.neutral_ease_time_s <= 0.0 ? 1.0 : dt / params_.neutral_ease_time_s;
    rise_ = lag_gain(dt, params_.activation_time_constant_s);
    fall_ = lag_gain(dt, params_.deactivation_time_constant_s);
    smooth_ = lag_gain(dt, params_.smoothing_time_constant_s);
  }
  const double ease_step = ease_step_;
  neutral_weight_ = std::clamp(neutral_weight_ + (input_stale ? ease_step : -ease_step), 0.0, 1.0);

  const double rise = rise_, fall = fall_, smooth = smooth_;
  const double w = neutral_weight_;
  for (std::size_t i = 0; i < layout_.size(); ++i) {
    const double target = (1.0 - w) * input[i] + w * neutral_[i];
    double gain = smooth;
    if (i < layout_.muscle_count()) gain = target > shaped_[i] ? rise : fall;
    shaped_[i] += gain * (target - shaped_[i]);
  }
  return shaped_;
}

}  // namespace facectl
