#pragma once

#include "control/safety/safety_state.hpp"

namespace facectl {

struct SafetyParams {
  double enable_ramp_s = 1.0;       // bumpless blend from measured to target
  double stop_timeout_s = 3.0;      // STOPPING gives up and disables after this
  int overrun_fault_count = 10;     // consecutive overruns that mean FAULT
  double input_timeout_s = 0.2;     // no fresh command for this long: ease to neutral
  double jog_speed_fraction = 0.1;  // JOG: of each actuator's max velocity
};

// What the tick observed, for step 8.
struct SafetyInputs {
  bool estop = false;
  bool bus_fault = false;
  bool io_fault = false;
  bool feedback_out_of_range = false;   // a measured position is outside its hardware range
  bool limit_breach = false;            // the command backstop acted on this tick
  bool drive_protection_fault = false;  // an actuator's drive protection latched FAULT
  int consecutive_overruns = 0;
  bool enable_request = false;
  bool shutdown_request = false;
  bool reset_request = false;
  bool jog_request = false;      // RUNNING -> JOG
  bool jog_end_request = false;  // JOG -> ENABLING (the ramp), then RUNNING
  bool at_rest = false;          // every actuator settled at its rest position
};

// Step 8 of the tick: the safety state machine. Pure logic over its inputs and
// the tick's dt, so tests can drive it tick by tick in simulated time.
class SafetyStateMachine {
 public:
  explicit SafetyStateMachine(const SafetyParams& params) : params_(params) {}

  // Returns the reason if the state changed on this step.
  TransitionReason step(const SafetyInputs& in, double dt);

  SafetyState state() const { return state_; }
  double time_in_state() const { return time_in_state_; }
  bool outputs_enabled() const { return commands_actuators(state_); }
  // 0..1 progress of the ENABLING blend from measured positions to the target.
  double enable_blend() const;

 private:
  TransitionReason go(SafetyState next, TransitionReason reason);

  SafetyParams params_;
  SafetyState state_ = SafetyState::kIdle;
  double time_in_state_ = 0.0;
};

}  // namespace facectl
