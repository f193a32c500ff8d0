// FAULT with the rig's per-actuator reactions (docs/SAFETY.md, "Fault
// reaction"): relax = output off at once; hold = brake to a stop under the
// actuator's own limits and stay; rest = go to rest under its limits and stay.
// Everything here runs on state changes, inside the tick: no allocation.
#include <algorithm>
#include <cmath>

#include "control/controller.hpp"

namespace facectl {

namespace {

// Where a limiter moving at its velocity comes to a stop if it brakes now,
// kept inside the soft range. No tick length enters it: the tick that found
// the fault may have been a long stall, and its dt in the distance would put
// the "stop" far ahead, for the limiter to speed toward (issue 19.1).
double stop_point(const ActuatorLimits& l, const LimiterState& s) {
  return std::clamp(committed_extreme(l, s, s.velocity), l.soft_min, l.soft_max);
}

}  // namespace

bool Controller::start_fault_reactions(SafetyState from, TransitionReason reason) {
  // Nothing was commanded before (IDLE) or the safety I/O itself failed:
  // everything is cut, as on e-stop.
  const bool live = commands_actuators(from);
  if (!live || reason == TransitionReason::kSafetyIoFault) return false;
  const std::size_t n = model_.actuators.size();
  for (std::size_t i = 0; i < n; ++i) {
    const ActuatorModel& a = model_.actuators[i];
    // An actuator whose own command breached its range is not trusted to hold.
    const bool breached = (flags_[i] & kLimitBreach) != 0;
    fault_driven_[i] =
        a.fault_reaction == FaultReaction::kRelax || breached || protection_relaxes(i) ? 0 : 1;
    fault_target_[i] =
        a.fault_reaction == FaultReaction::kRest ? a.rest : stop_point(a.limits, limiter_[i]);
  }
  if (model_.mapping.mechanism) {
    // All struts share one reaction (checked when the model is built): the
    // pose brakes in its own DOFs, or goes to the rest pose.
    const MandibleMechanism& mech = *model_.mapping.mechanism;
    const bool rest =
        model_.actuators[mech.strut[0].actuator].fault_reaction == FaultReaction::kRest;
    fault_pose_ = model_.mandible_rest;
    if (!rest) {
      fault_pose_ = {stop_point(model_.mandible_limits[0], pose_limiter_[0]),
                     stop_point(model_.mandible_limits[1], pose_limiter_[1]),
                     stop_point(model_.mandible_limits[2], pose_limiter_[2])};
    }
  }
  relax_uncommandable(false);
  return fault_driving_;
}

void Controller::relax_uncommandable(bool io_fault) {
  // An actuator on a bus that reports a fault cannot be commanded; on a
  // safety-I/O fault nothing is trusted. Both relax, whatever the reaction.
  bool changed = !fault_driving_;
  for (std::size_t b = 0; b < bus_count_; ++b) {
    if (!io_fault && !bus_faulted_[b]) continue;
    const BusModel& bus = model_.buses[b];
    for (std::size_t i = bus.first; i < bus.first + bus.count; ++i) {
      changed = changed || fault_driven_[i] != 0;
      fault_driven_[i] = 0;
    }
  }
  // An actuator measured outside its hardware range (jammed, forced, a broken
  // encoder) is not held: holding would drive it at full effort toward a point
  // far from where it is. Likewise the jaw's struts when their measured pose is
  // outside the envelope or no pose at all. At entry and on every later tick.
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    if (fault_driven_[i] != 0 && (!measured_in_range(i) || protection_relaxes(i))) {
      fault_driven_[i] = 0;
      changed = true;
    }
  }
  if (model_.mapping.mechanism && jaw_out_of_envelope_) {
    const MandibleMechanism& mech = *model_.mapping.mechanism;
    for (std::size_t s = 0; s < mech.struts(); ++s) {
      changed = changed || fault_driven_[mech.strut[s].actuator] != 0;
      fault_driven_[mech.strut[s].actuator] = 0;
    }
  }
  changed = relax_split_mechanism() || changed;
  if (!changed) return;
  fault_driving_ = apply_fault_enables();
  // A backend that enables per board may have switched off more struts.
  if (fault_driving_ && relax_split_mechanism()) fault_driving_ = apply_fault_enables();
}

bool Controller::relax_split_mechanism() {
  // The struts move together by IK, so one relaxed strut relaxes them all.
  if (!model_.mapping.mechanism) return false;
  const MandibleMechanism& mech = *model_.mapping.mechanism;
  bool all = true, any = false;
  for (std::size_t s = 0; s < mech.struts(); ++s) {
    all = all && fault_driven_[mech.strut[s].actuator] != 0;
    any = any || fault_driven_[mech.strut[s].actuator] != 0;
  }
  if (all || !any) return false;
  for (std::size_t s = 0; s < mech.struts(); ++s) fault_driven_[mech.strut[s].actuator] = 0;
  return true;
}

bool Controller::apply_fault_enables() {
  // Buses with something to drive get the per-actuator flags (which a
  // backend may clear further); the others, and any left with nothing on,
  // are disabled whole.
  bool any = false;
  for (std::size_t b = 0; b < bus_count_; ++b) {
    const BusModel& bus = model_.buses[b];
    const std::span<std::uint8_t> flags(fault_driven_.data() + bus.first, bus.count);
    const auto on = [&] {
      return std::any_of(flags.begin(), flags.end(), [](std::uint8_t f) { return f != 0; });
    };
    if (on()) buses_[b]->set_actuators_enabled(flags);
    bus_driven_[b] = on();
    if (!bus_driven_[b]) buses_[b]->set_enabled(false);
    any = any || bus_driven_[b];
  }
  // Power-enable stays on only while some actuator holds or rests.
  if (!any) {
    for (std::size_t b = 0; b < bus_count_; ++b) buses_[b]->set_enabled(false);
    io_.set_power_enable(false);
  }
  return any;
}

bool Controller::fault_reaction_moving() const {
  // Standing still means no commanded velocity at all: the limiter settles
  // exactly on its target (rounding aside, far below this tolerance).
  const auto moving = [](const ActuatorLimits& l, const LimiterState& s) {
    return std::fabs(s.velocity) > 1e-9 * l.max_velocity;
  };
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    if (fault_driven_[i] != 0 && moving(model_.actuators[i].limits, limiter_[i])) return true;
  }
  // The struts follow the pose's limiters while they are driven.
  const MandibleMechanism* mech = model_.mapping.mechanism ? &*model_.mapping.mechanism : nullptr;
  if (mech == nullptr || fault_driven_[mech->strut[0].actuator] == 0) return false;
  for (std::size_t k = 0; k < 3; ++k) {
    if (moving(model_.mandible_limits[k], pose_limiter_[k])) return true;
  }
  return false;
}

void Controller::release_outputs() {
  for (std::size_t b = 0; b < bus_count_; ++b) buses_[b]->set_enabled(false);
  io_.set_power_enable(false);
  fault_driving_ = false;
  fault_holding_.store(false, std::memory_order_relaxed);
  fault_moving_.store(false, std::memory_order_relaxed);
}

}  // namespace facectl
