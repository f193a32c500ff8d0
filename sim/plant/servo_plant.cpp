#include "sim/plant/servo_plant.hpp"

#include <algorithm>
#include <cmath>

namespace facectl::sim {
namespace {

constexpr double kTwoPi = 6.283185307179586;
// PD is integrated (semi-implicit Euler) in steps of at most this, so that a
// stiff servo stays stable whatever the tick.
constexpr double kPdMaxStep_s = 0.0005;

}  // namespace

ServoPlant::ServoPlant(const ServoPlantParams& params, double initial_position)
    : params_(params),
      active_command_(initial_position),
      motor_(initial_position),
      output_(initial_position),
      noise_(params.seed),
      thermal_(params.thermal, params.name) {
  const double w = kTwoPi * params.natural_frequency_hz;
  kp_ = w * w;
  kd_ = 2.0 * params.damping_ratio * w;
}

void ServoPlant::set_enabled(bool enabled) {
  if (enabled != enabled_) {
    delay_size_ = 0;
    active_command_ = motor_;
    velocity_ = 0.0;
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

// The velocity the limits allow, given the one wanted over the next `dt`.
double ServoPlant::limit_velocity(double v_wanted, double dt) const {
  double v = std::clamp(v_wanted, -params_.max_velocity, params_.max_velocity);
  if (params_.max_acceleration > 0.0) {
    const double dv = params_.max_acceleration * dt;
    v = std::clamp(v, velocity_ - dv, velocity_ + dv);
  }
  return v;
}

void ServoPlant::step_first_order(double dt) {
  const double error = active_command_ - motor_;
  if (std::fabs(error) <= params_.deadband) {
    velocity_ = 0.0;  // the amplifier is off and the gear train holds
    return;
  }
  if (dt != gain_dt_) {  // ticks repeat their dt: one exp per change, not per step
    gain_dt_ = dt;
    gain_ = params_.time_constant_s <= 0.0 ? 1.0 : 1.0 - std::exp(-dt / params_.time_constant_s);
  }
  const double gain = gain_;
  const double max_step = params_.max_velocity * dt;
  double step = std::clamp(gain * error, -max_step, max_step);
  if (params_.max_acceleration > 0.0) {
    // A profiled servo brakes in time to stop at the command: never faster
    // than sqrt(2·a·|error|), and never changing speed by more than a·dt.
    const double brake = std::sqrt(2.0 * params_.max_acceleration * std::fabs(error)) * dt;
    step = std::clamp(step, -brake, brake);
    step = limit_velocity(step / dt, dt) * dt;
  }
  motor_ += step;
  velocity_ = step / dt;
}

void ServoPlant::step_pd(double dt) {
  if (dt != gain_dt_) {  // ticks repeat their dt: work the sub-steps out once
    gain_dt_ = dt;
    pd_steps_ = std::max(1, static_cast<int>(std::ceil(dt / kPdMaxStep_s)));
    pd_h_ = dt / pd_steps_;
  }
  const double kp = kp_, kd = kd_, h = pd_h_;
  const int n = pd_steps_;
  for (int i = 0; i < n; ++i) {
    const double error = active_command_ - motor_;
    if (std::fabs(error) <= params_.deadband) {
      velocity_ = 0.0;
      continue;
    }
    double a = kp * error - kd * velocity_;
    if (params_.max_acceleration > 0.0) {
      a = std::clamp(a, -params_.max_acceleration, params_.max_acceleration);
    }
    velocity_ = std::clamp(velocity_ + a * h, -params_.max_velocity, params_.max_velocity);
    motor_ += velocity_ * h;
  }
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
  if (dt <= 0.0) return;
  if (enabled_) {
    if (params_.model == PlantModel::kPd) {
      step_pd(dt);
    } else {
      step_first_order(dt);
    }
    // Gear play: the output follows only once the motor takes up the slack.
    const double half = 0.5 * params_.backlash;
    output_ = std::clamp(output_, motor_ - half, motor_ + half);
  }
  thermal_.step(now_ns, dt, enabled_, output_, active_command_ - motor_);
}

double ServoPlant::measured() {
  if (params_.noise_stddev <= 0.0) return output_;
  return output_ + params_.noise_stddev * noise_.next();
}

}  // namespace facectl::sim
