#pragma once

#include <cstdint>

#include "control/controller_model.hpp"
#include "control/limits/trajectory_limiter.hpp"

namespace facectl {

// Actuator coupled limits Σ a_i·x_i <= b made exact (docs/SAFETY.md, "Actuator
// coupled limits"): each tick, each limit becomes position bounds for the
// trajectory limiters of its actuators, which never cross them.
//
// Per limit: m_i = actuator i's committed_extreme() in the direction of a_i,
// slack = b - Σ a_i·m_i. The slack is shared among the actuators by their
// demand a_i·(target_i - m_i) > 0 (in proportion when it does not cover every
// demand; what is left over, equally among all terms), and actuator i's bound
// is m_i + share_i / a_i. So Σ a_i·bound_i = b, and, the limiter's committed
// extreme never passing its bound, Σ a_i·x_i <= Σ a_i·m_i <= b on every tick
// after: slack >= 0 by induction. With slack < 0 (the actuators started
// beyond the limit), every share is 0: nothing moves the sum up.
//
// An actuator in several limits takes the tightest bounds, intersected with
// its soft range (a coupled bound wins where they cross: only an actuator
// enabled outside its soft range can meet that).
//
// Fills lo[i], hi[i] for every actuator in some limit (at most
// kMaxActuators = 64) and returns them as a bit set; bounded time, no
// allocation.
std::uint64_t coupled_position_bounds(const CoupledConstraints& limits,
                                      const ActuatorModel* actuators, const LimiterState* state,
                                      const double* target, double* lo, double* hi);

}  // namespace facectl
