#include "control/safety/safety_state_machine.hpp"

#include <algorithm>

namespace facectl {

TransitionReason SafetyStateMachine::go(SafetyState next, TransitionReason reason) {
  state_ = next;
  time_in_state_ = 0.0;
  return reason;
}

double SafetyStateMachine::enable_blend() const {
  if (state_ != SafetyState::kEnabling) return state_ == SafetyState::kIdle ? 0.0 : 1.0;
  if (params_.enable_ramp_s <= 0.0) return 1.0;
  const double u = std::clamp(time_in_state_ / params_.enable_ramp_s, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);  // smoothstep: zero slope at both ends
}

TransitionReason SafetyStateMachine::step(const SafetyInputs& in, double dt) {
  time_in_state_ += dt;

  // E-stop wins over everything, from every state.
  if (in.estop) {
    return state_ == SafetyState::kEstop ? TransitionReason::kNone
                                         : go(SafetyState::kEstop, TransitionReason::kEstopInput);
  }
  if (state_ == SafetyState::kEstop) {
    // Released: stays latched until somebody resets it.
    return in.reset_request ? go(SafetyState::kIdle, TransitionReason::kFaultReset)
                            : TransitionReason::kNone;
  }
  if (state_ == SafetyState::kFault) {
    const bool cleared = !in.bus_fault && !in.io_fault && !in.drive_protection_fault;
    return in.reset_request && cleared ? go(SafetyState::kIdle, TransitionReason::kFaultReset)
                                       : TransitionReason::kNone;
  }

  // Faults, from any state that may drive outputs or wants to.
  if (in.io_fault) return go(SafetyState::kFault, TransitionReason::kSafetyIoFault);
  if (in.limit_breach) return go(SafetyState::kFault, TransitionReason::kLimitBreach);
  if (in.bus_fault) return go(SafetyState::kFault, TransitionReason::kBusFault);
  if (params_.overrun_fault_count > 0 && in.consecutive_overruns >= params_.overrun_fault_count) {
    return go(SafetyState::kFault, TransitionReason::kOverrunStorm);
  }

  // Drive-level protection: from any driving state, and it refuses to enable.
  if (in.drive_protection_fault && (state_ != SafetyState::kIdle || in.enable_request)) {
    return go(SafetyState::kFault, TransitionReason::kDriveProtection);
  }
  if (in.feedback_out_of_range && state_ != SafetyState::kIdle) {
    return go(SafetyState::kFault, TransitionReason::kFeedbackOutOfRange);
  }

  switch (state_) {
    case SafetyState::kIdle:
      // Never enable onto an actuator that is already beyond its range.
      if (in.enable_request && !in.shutdown_request && in.feedback_out_of_range) {
        return go(SafetyState::kFault, TransitionReason::kFeedbackOutOfRange);
      }
      if (in.enable_request && !in.shutdown_request) {
        return go(SafetyState::kEnabling, TransitionReason::kEnableRequested);
      }
      break;
    case SafetyState::kEnabling:
      if (in.shutdown_request)
        return go(SafetyState::kStopping, TransitionReason::kShutdownRequested);
      if (time_in_state_ >= params_.enable_ramp_s) {
        return go(SafetyState::kRunning, TransitionReason::kEnableRampDone);
      }
      break;
    case SafetyState::kRunning:
      if (in.shutdown_request)
        return go(SafetyState::kStopping, TransitionReason::kShutdownRequested);
      if (in.jog_request) return go(SafetyState::kJog, TransitionReason::kJogRequested);
      break;
    case SafetyState::kJog:
      if (in.shutdown_request)
        return go(SafetyState::kStopping, TransitionReason::kShutdownRequested);
      // Back through the bumpless ramp: the face input's target may be far
      // from where the jog left the head.
      if (in.jog_end_request) return go(SafetyState::kEnabling, TransitionReason::kJogEnded);
      break;
    case SafetyState::kStopping:
      if (in.at_rest) return go(SafetyState::kIdle, TransitionReason::kRestReached);
      if (time_in_state_ >= params_.stop_timeout_s) {
        return go(SafetyState::kIdle, TransitionReason::kStopTimeout);
      }
      break;
    default:
      break;
  }
  return TransitionReason::kNone;
}

}  // namespace facectl
