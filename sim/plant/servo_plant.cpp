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
      latency_ns_(static_cast<std::int64_t>(params.latency_s * 1e9)),
      half_backlash_(0.5 * params.backlash),
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

// The velocity the limits allow, given the one wanted over the next `dt`.
double ServoPlant::limit_velocity(double v_wanted, double dt) const {
  double v = std::clamp(v_wanted, -params_.max_velocity, params_.max_velocity);
  if (params_.max_acceleration > 0.0) {
    const double dv = params_.max_acceleration * dt;
    v = std::clamp(v, velocity_ - dv, velocity_ + dv);
  }
  return v;
}

// Ticks repeat their dt: the model's step constants (an exp or a ceil) are
// worked out once per change, not per step; kept out of the per-tick loop.
[[gnu::noinline]] void ServoPlant::set_dt(double dt) {
  step_dt_ = dt;
  if (params_.model == PlantModel::kPd) {
    pd_steps_ = std::max(1, static_cast<int>(std::ceil(dt / kPdMaxStep_s)));
    pd_h_ = dt / pd_steps_;
  } else {
    gain_ = params_.time_constant_s <= 0.0 ? 1.0 : 1.0 - std::exp(-dt / params_.time_constant_s);
  }
}

void ServoPlant::step_first_order(double dt) {
  const double error = active_command_ - motor_;
  if (std::fabs(error) <= params_.deadband) {
    velocity_ = 0.0;  // the amplifier is off and the gear train holds
    return;
  }
  if (dt != step_dt_) set_dt(dt);
  const double max_step = params_.max_velocity * dt;
  double step = std::clamp(gain_ * error, -max_step, max_step);
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
  if (dt != step_dt_) set_dt(dt);
  const double kp = kp_, kd = kd_, h = pd_h_;
  const double deadband = params_.deadband;
  const double max_a = params_.max_acceleration, max_v = params_.max_velocity;
  // The state in locals, so that the sub-steps keep it in registers.
  double x = motor_, v = velocity_;
  for (int i = 0; i < pd_steps_; ++i) {
    const double error = active_command_ - x;
    if (std::fabs(error) <= deadband) {
      v = 0.0;
      continue;
    }
    double a = kp * error - kd * v;
    if (max_a > 0.0) a = std::clamp(a, -max_a, max_a);
    v = std::clamp(v + a * h, -max_v, max_v);
    x += v * h;
  }
  motor_ = x;
  velocity_ = v;
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
    output_ = std::clamp(output_, motor_ - half_backlash_, motor_ + half_backlash_);
    if (motor_ > block_above_) {
      motor_ = block_above_;
      velocity_ = 0.0;
    }
    output_ = std::min(output_, block_above_);
  }
  thermal_.step(now_ns, dt, enabled_, output_, active_command_ - motor_);
}

double ServoPlant::measured() {
  if (params_.noise_stddev <= 0.0) return output_;
  return output_ + params_.noise_stddev * noise_.next();
}

// Flattened: every step of a servo inlines into the loop (not a call per stage).
[[gnu::flatten]] const char* advance_and_measure(std::span<ServoPlant> plants, std::int64_t now_ns,
                                                 std::span<double> measured) {
  const std::size_t n = std::min(plants.size(), measured.size());
  const char* first_fault = nullptr;
  for (std::size_t i = 0; i < n; ++i) {
    ServoPlant& plant = plants[i];
    plant.advance(now_ns);
    measured[i] = plant.measured();
    if (first_fault == nullptr) first_fault = plant.fault();
  }
  return first_fault;
}

}  // namespace facectl::sim
