#include "control/safety/safety_state.hpp"

namespace facectl {

std::string_view to_string(SafetyState state) {
  switch (state) {
    case SafetyState::kIdle:
      return "IDLE";
    case SafetyState::kEnabling:
      return "ENABLING";
    case SafetyState::kRunning:
      return "RUNNING";
    case SafetyState::kStopping:
      return "STOPPING";
    case SafetyState::kFault:
      return "FAULT";
    case SafetyState::kEstop:
      return "ESTOP";
    case SafetyState::kJog:
      return "JOG";
  }
  return "?";
}

std::string_view to_string(TransitionReason reason) {
  switch (reason) {
    case TransitionReason::kNone:
      return "none";
    case TransitionReason::kEnableRequested:
      return "enable requested";
    case TransitionReason::kEnableRampDone:
      return "enable ramp complete";
    case TransitionReason::kShutdownRequested:
      return "shutdown requested";
    case TransitionReason::kRestReached:
      return "rest pose reached";
    case TransitionReason::kStopTimeout:
      return "stop timeout: disabled before rest was reached";
    case TransitionReason::kEstopInput:
      return "e-stop input active";
    case TransitionReason::kBusFault:
      return "bus fault";
    case TransitionReason::kOverrunStorm:
      return "consecutive deadline overruns";
    case TransitionReason::kSafetyIoFault:
      return "safety I/O fault";
    case TransitionReason::kFeedbackOutOfRange:
      return "actuator measured outside its hardware range";
    case TransitionReason::kLimitBreach:
      return "limit breach: a command outside the hardware range was stopped";
    case TransitionReason::kFaultReset:
      return "reset";
    case TransitionReason::kJogRequested:
      return "jog requested";
    case TransitionReason::kJogEnded:
      return "jog ended";
    case TransitionReason::kDriveProtection:
      return "drive protection";
  }
  return "?";
}

}  // namespace facectl
