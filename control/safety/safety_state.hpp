#pragma once

#include <cstdint>
#include <string_view>

namespace facectl {

enum class SafetyState : std::uint8_t {
  kIdle,      // outputs disabled, power-enable off
  kEnabling,  // bumpless ramp from measured positions to the live target
  kRunning,
  kStopping,  // easing to the rest pose before disabling (shutdown)
  kFault,     // each actuator by its fault reaction (relax, hold, rest); IDLE on reset
  kEstop,     // nothing transmitted, power-enable off; leaves to IDLE on release + reset
  kJog,       // from RUNNING: the face input is ignored, every actuator holds but the
              // one an operator jogs, within its soft limits at a capped speed; leaves
              // through ENABLING
};

// ENABLING, RUNNING, JOG and STOPPING command the actuators; the other states
// do not (FAULT only by its per-actuator reactions).
constexpr bool commands_actuators(SafetyState s) {
  return s == SafetyState::kEnabling || s == SafetyState::kRunning || s == SafetyState::kJog ||
         s == SafetyState::kStopping;
}

enum class TransitionReason : std::uint8_t {
  kNone,
  kEnableRequested,
  kEnableRampDone,
  kShutdownRequested,
  kRestReached,
  kStopTimeout,
  kEstopInput,
  kBusFault,
  kOverrunStorm,
  kSafetyIoFault,
  kFeedbackOutOfRange,
  kLimitBreach,
  kFaultReset,
  kJogRequested,
  kJogEnded,
  kDriveProtection,  // an actuator's drive-level protection (docs/SAFETY.md)
};

std::string_view to_string(SafetyState state);
std::string_view to_string(TransitionReason reason);

// A state change, as logged and written to telemetry.
struct TransitionEvent {
  std::uint64_t tick = 0;
  double time_s = 0.0;
  SafetyState from = SafetyState::kIdle;
  SafetyState to = SafetyState::kIdle;
  TransitionReason reason = TransitionReason::kNone;
  char detail[128] = {};  // e.g. the bus and its fault; fixed size for the RT ring
};

}  // namespace facectl
