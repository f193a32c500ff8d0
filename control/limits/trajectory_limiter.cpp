#include "control/limits/trajectory_limiter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace facectl {
namespace {

// Relative tolerance for deciding that a bound "fired", so that floating
// rounding on an exactly tracked trajectory is not reported as a limit.
constexpr double kFireTolerance = 1e-12;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

double braking_speed(double distance, double max_acceleration, double dt) {
  if (distance <= 0.0) return 0.0;
  // Positive root of v²/(2A) + v·dt = d.
  const double a = max_acceleration;
  return a * (std::sqrt(dt * dt + 2.0 * distance / a) - dt);
}

double jerk_stopping_distance(double v, double a, double max_acceleration, double max_jerk) {
  const double amax = max_acceleration, j = max_jerk;
  if (!(v > 0.0) && !(a > 0.0)) return 0.0;  // standing still or already turning back
  double x = 0.0;
  const auto phase = [&](double jerk, double t) {
    t = std::max(t, 0.0);
    x += v * t + a * t * t / 2.0 + jerk * t * t * t / 6.0;
    v += a * t + jerk * t * t / 2.0;
    a += jerk * t;
  };
  if (a < 0.0 && a * a / (2.0 * j) >= v) {
    // Braking harder than needed: the speed reaches 0 while a ramps back up.
    phase(j, (-a - std::sqrt(std::max(a * a - 2.0 * j * v, 0.0))) / j);
    return x;
  }
  // Ramp to the deepest deceleration needed (at most A), hold it, ramp back to 0.
  const double deepest = -std::min(amax, std::sqrt(j * v + a * a / 2.0));
  if (a > deepest) phase(-j, (a - deepest) / j);
  const double hold = std::min(a, deepest);
  phase(0.0, (v - hold * hold / (2.0 * j)) / -hold);
  phase(j, -hold / j);
  return x;
}

namespace {

// One step inside [lo, hi]; kWithin: the bounds may be tighter than the soft
// range (compiled out of the plain step, which runs for every actuator).
template <bool kWithin>
LimitFlags step(const ActuatorLimits& limits, LimiterState& state, double target, double dt,
                double lo, double hi) {
  LimitFlags flags = 0;
  if (!(dt > 0.0) || !std::isfinite(dt)) return kLimitInvalid;  // no time passed: no motion
  if (!std::isfinite(target)) {
    // A non-finite target cannot reach here through the sanitiser, but a
    // mapping can overflow: brake to a stop where we are instead.
    target = state.position;
    flags |= kLimitInvalid;
  }
  const double a_max = limits.max_acceleration;
  const double v_max = limits.max_velocity;
  const double x = state.position;
  const double v = state.velocity;

  const double soft = std::clamp(target, limits.soft_min, limits.soft_max);
  if (soft != target) flags |= kLimitPosition;
  double r = soft;
  if constexpr (kWithin) {
    r = std::clamp(soft, lo, hi);
    if (r != soft) flags |= kLimitCoupled;
  }

  // Goal velocity: the fastest approach to the target that can still stop on it.
  const double error = r - x;
  const double distance = std::fabs(error);
  // Under a jerk limit, deceleration ramps in over A/J, which adds about
  // v·A/(2J) to the stopping distance: plan the approach with that delay.
  const double ramp = limits.max_jerk > 0.0 ? a_max / (2.0 * limits.max_jerk) : 0.0;
  const double goal_speed = braking_speed(distance, a_max, dt + ramp);
  double v_goal = std::copysign(std::min(goal_speed, v_max), error);
  if (goal_speed > v_max * (1.0 + kFireTolerance) && std::fabs(error) > 0.0) {
    flags |= kLimitVelocity;
  }

  // Never head into a soft limit (or position bound) faster than one can
  // stop before it. No velocity below (goal, accelerated or jerk-limited) can
  // be faster than `cap`, so a bound farther than the stopping distance from
  // `cap` cannot bind this step: its square root is skipped (the common case;
  // the result is the same). The margin covers the rounding of braking_speed.
  const double cap = std::max(v_max, std::fabs(v) + a_max * dt);
  const double reach = (cap * cap + 2.0 * a_max * cap * (dt + ramp)) * (1.0 + 1e-6);
  const auto bound = [&](double d) {
    return 2.0 * a_max * d >= reach ? std::numeric_limits<double>::infinity()
                                    : braking_speed(d, a_max, dt + ramp);
  };
  const double v_hi = bound(hi - x);
  const double v_lo = -bound(x - lo);
  if (v_goal > v_hi || v_goal < v_lo) {
    const bool tighter = v_goal > v_hi ? hi < limits.soft_max : lo > limits.soft_min;
    flags |= kWithin && tighter ? kLimitCoupled : kLimitApproach;
    v_goal = std::clamp(v_goal, v_lo, v_hi);
  }

  // Acceleration bound.
  double v_new = std::clamp(v_goal, v - a_max * dt, v + a_max * dt);
  if (v_new != v_goal &&
      std::fabs(v_new - v_goal) > kFireTolerance * std::max(1.0, std::fabs(v_goal))) {
    flags |= kLimitAcceleration;
  }

  // Optional jerk bound: track the goal velocity with an acceleration that can
  // ramp down in time (a = sqrt(2·J·|Δv|)), then bound its change per tick.
  // It yields to the velocity, acceleration and position bounds above.
  if (limits.max_jerk > 0.0) {
    const double j_max = limits.max_jerk;
    const double dv = v_goal - v;
    const double a_want = std::copysign(
        std::min({a_max, std::sqrt(2.0 * j_max * std::fabs(dv)), std::fabs(dv) / dt}), dv);
    double a_jerk =
        std::clamp(a_want, state.acceleration - j_max * dt, state.acceleration + j_max * dt);
    double v_jerk = v + a_jerk * dt;
    // Tracking the goal lags it; once the brake that the jerk limit allows
    // from the next state would no longer stop short of what lies ahead
    // (the target, or the range's end), brake now at the jerk limit. The
    // margin of one more step covers the discrete integration.
    if (v_jerk != 0.0) {
      const double ahead = v_jerk > 0.0 ? 1.0 : -1.0;
      const double room =
          std::min(ahead > 0.0 ? hi - x : x - lo, ahead * error > 0.0 ? distance : kInfinity);
      const double speed = ahead * v_jerk;
      // A bound on any jerk-limited stop from this speed (the ramp to -A adds
      // at most A²/2J of speed and lasts at most 2A/J; the ramp out A/J):
      // beyond it the exact distance is not needed (the common case).
      const double top = speed + a_max * a_max / (2.0 * j_max);
      const bool far = top * top / (2.0 * a_max) + top * 3.0 * a_max / j_max + 2.0 * speed * dt <=
                       room * (1.0 - 1e-9);
      if (!far &&
          jerk_stopping_distance(speed, ahead * a_jerk, a_max, j_max) + 2.0 * speed * dt > room) {
        a_jerk = ahead * std::max(ahead * state.acceleration - j_max * dt, -a_max);
        v_jerk = v + a_jerk * dt;
      }
    }
    const double side = error >= 0.0 ? 1.0 : -1.0;
    // The ramp in the goal only plans the approach; a jerk-shaped step that
    // lags it must still be able to stop on the target at full braking, as
    // the plain step always can, or it would pass the target and ring.
    const double toward = side * v_jerk;
    const bool stops_on_target =
        toward > 0.0 ? toward * toward + 2.0 * a_max * toward * dt <= 2.0 * a_max * distance
                     : error != 0.0 || v_jerk == 0.0;  // on the target: stay
    // Nor may the acceleration left over from a braking step push the
    // motion back past standing still when the goal is still ahead.
    const bool turns_back = v_jerk * v_goal < 0.0 && v * v_goal >= 0.0;
    if (stops_on_target && !turns_back && v_jerk <= v_hi && v_jerk >= v_lo &&
        std::fabs(v_jerk) <= std::max(v_max, std::fabs(v)) && std::fabs(a_jerk) <= a_max) {
      if (a_jerk != a_want) flags |= kLimitJerk;
      v_new = v_jerk;
    } else {
      flags |= kLimitJerkYielded;
    }
  }

  // Backstop: only rounding or a broken invariant can get here.
  if (v_new > v_hi || v_new < v_lo) {
    v_new = std::clamp(v_new, v_lo, v_hi);
    if (std::fabs(v_new - v) > a_max * dt * (1.0 + 1e-9)) flags |= kLimitBreach;
  }

  double x_new = x + v_new * dt;
  if (x_new > hi || x_new < lo) {
    // Reachable only through rounding when x was inside; pin to the range.
    const bool was_inside = x <= hi && x >= lo;
    if (was_inside) {
      const double pinned = std::clamp(x_new, lo, hi);
      if (std::fabs(pinned - x_new) > 1e-12) flags |= kLimitBreach;
      x_new = pinned;
      v_new = (x_new - x) / dt;
    }
  }

  state.acceleration = (v_new - v) / dt;
  state.velocity = v_new;
  state.position = x_new;
  return flags;
}

}  // namespace

std::uint8_t limit_step(const ActuatorLimits& limits, LimiterState& state, double target,
                        double dt) {
  return static_cast<std::uint8_t>(
      step<false>(limits, state, target, dt, limits.soft_min, limits.soft_max));
}

LimitFlags limit_step_within(const ActuatorLimits& limits, LimiterState& state, double target,
                             double dt, double lo, double hi) {
  return step<true>(limits, state, target, dt, lo, hi);
}

double stopping_distance(const ActuatorLimits& l, double v, double dt) {
  const double ramp = l.max_jerk > 0.0 ? l.max_acceleration / (2.0 * l.max_jerk) : 0.0;
  return v * v / (2.0 * l.max_acceleration) + v * (dt + ramp);
}

double committed_extreme(const ActuatorLimits& l, const LimiterState& s, double direction) {
  const double v = direction > 0.0 ? s.velocity : -s.velocity;  // speed toward `direction`
  if (!(v > 0.0)) return s.position;
  return s.position + std::copysign(stopping_distance(l, v, 0.0), direction);
}

}  // namespace facectl
