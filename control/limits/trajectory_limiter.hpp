#pragma once

#include <cstdint>

#include "control/actuator_model.hpp"

namespace facectl {

// The commanded trajectory of one actuator (SI units of the actuator).
struct LimiterState {
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

// Advances `state` one tick of real duration `dt` toward `target`, so that the
// commanded trajectory never leaves the soft range and never exceeds the
// velocity or acceleration bounds. Returns the
// LimitFlag bits of the limits that shaped the motion.
//
// Integration is semi-implicit Euler: x' = x + v'·dt, so the finite
// differences of the commanded positions are exactly the limited velocity and
// acceleration. The braking bound v'²/(2A) + v'·dt ≤ d toward every boundary is
// solved with this tick's dt; decelerating at A always satisfies it on the next
// tick whatever that tick's dt is, so late and early ticks stay inside the
// range (docs/SAFETY.md derives this). A NaN/inf target brakes to a stop; a
// non-positive dt moves nothing (both flagged kLimitInvalid).
std::uint8_t limit_step(const ActuatorLimits& limits, LimiterState& state, double target,
                        double dt);

// As limit_step, inside the position bounds [lo, hi] (within the soft range)
// instead of the soft range: the same braking argument keeps the trajectory
// inside them as long as neither bound is ever moved past the actuator's
// committed_extreme() toward it. kLimitPosition and kLimitApproach report the
// soft range; kLimitCoupled a tighter bound that shaped the step.
LimitFlags limit_step_within(const ActuatorLimits& limits, LimiterState& state, double target,
                             double dt, double lo, double hi);

// The farthest point in `direction` (+1 or -1) that the limiter has
// committed to: its position, plus, when it moves that way at speed v, the
// braking distance v²/2A + v·A/(2J) that every step keeps to its bound (the
// step's own v·dt is already travelled). The limiter can always stop there,
// within its acceleration limit, whatever the next tick's dt.
double committed_extreme(const ActuatorLimits& limits, const LimiterState& state, double direction);

// Highest speed v' that can still stop within `distance` after moving v'·dt.
double braking_speed(double distance, double max_acceleration, double dt);

// How far a jerk-limited brake travels from speed v >= 0 and acceleration a
// (positive: speeding up) before it stands still: deceleration ramps in at
// the jerk limit J to at most A, holds, and ramps out (continuous time).
double jerk_stopping_distance(double v, double a, double max_acceleration, double max_jerk);

// How far the limiter may still travel at speed v before it stands still: its
// own approach plan (docs/SAFETY.md), v²/2A + v·(dt + A/2J).
double stopping_distance(const ActuatorLimits& limits, double v, double dt);

}  // namespace facectl
