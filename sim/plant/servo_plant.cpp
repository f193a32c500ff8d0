#include "sim/plant/servo_plant.hpp"

#include <algorithm>
#include <cmath>

namespace facectl::sim {

ServoPlant::ServoPlant(const ServoPlantParams& params, double initial_position)
    : params_(params),
      active_command_(initial_position),
      position_(initial_position),
      rng_(params.seed) {}

void ServoPlant::set_enabled(bool enabled) {
  if (enabled != enabled_) {
    delay_size_ = 0;
    active_command_ = position_;
  }
  enabled_ = enabled;
}

void ServoPlant::command(std::int64_t now_ns, double position) {
  if (delay_size_ == kDelaySlots) {
    // Full: the oldest pending command is overtaken by newer ones anyway.
    delay_head_ = (delay_head_ + 1) % kDelaySlots;
    --delay_size_;
  }
  const auto latency_ns = static_cast<std::int64_t>(params_.latency_s * 1e9);
  delay_[(delay_head_ + delay_size_) % kDelaySlots] = {now_ns + latency_ns, position};
  ++delay_size_;
}

void ServoPlant::advance(std::int64_t now_ns) {
  if (last_ns_ < 0) last_ns_ = now_ns;
  // Commands whose latency has elapsed become active, in order.
  while (delay_size_ > 0 && delay_[delay_head_].at_ns <= now_ns) {
    active_command_ = delay_[delay_head_].value;
    delay_head_ = (delay_head_ + 1) % kDelaySlots;
    --delay_size_;
  }
  const double dt = static_cast<double>(now_ns - last_ns_) * 1e-9;
  last_ns_ = now_ns;
  if (!enabled_ || dt <= 0.0) return;
  const double gain =
      params_.time_constant_s <= 0.0 ? 1.0 : 1.0 - std::exp(-dt / params_.time_constant_s);
  const double max_step = params_.max_velocity * dt;
  position_ += std::clamp(gain * (active_command_ - position_), -max_step, max_step);
}

double ServoPlant::measured() {
  if (params_.noise_stddev <= 0.0) return position_;
  return position_ + params_.noise_stddev * noise_(rng_);
}

}  // namespace facectl::sim
