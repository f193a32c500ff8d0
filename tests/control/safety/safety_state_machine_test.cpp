#include "control/safety/safety_state_machine.hpp"

#include <gtest/gtest.h>

namespace facectl {
namespace {

constexpr double kDt = 0.001;

SafetyStateMachine running_machine(const SafetyParams& p = {}) {
  SafetyStateMachine sm(p);
  SafetyInputs in;
  in.enable_request = true;
  sm.step(in, kDt);
  in.enable_request = false;
  while (sm.state() != SafetyState::kRunning) sm.step(in, kDt);
  return sm;
}

TEST(SafetyStateMachine, EnablesThroughARampThenRuns) {
  SafetyParams p;
  p.enable_ramp_s = 0.5;
  SafetyStateMachine sm(p);
  SafetyInputs in;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kNone);
  EXPECT_FALSE(sm.outputs_enabled());
  in.enable_request = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kEnableRequested);
  EXPECT_EQ(sm.state(), SafetyState::kEnabling);
  EXPECT_DOUBLE_EQ(sm.enable_blend(), 0.0);
  in.enable_request = false;
  int ticks = 0;
  while (sm.state() == SafetyState::kEnabling) {
    const double before = sm.enable_blend();
    sm.step(in, kDt);
    if (sm.state() == SafetyState::kEnabling) {
      ASSERT_GE(sm.enable_blend(), before);
    }
    ++ticks;
  }
  EXPECT_EQ(sm.state(), SafetyState::kRunning);
  EXPECT_NEAR(ticks, 500, 1);
}

TEST(SafetyStateMachine, JogIsEnteredOnlyFromRunningAndLeftBackToIt) {
  SafetyStateMachine idle{SafetyParams{}};
  SafetyInputs in;
  in.jog_request = true;
  EXPECT_EQ(idle.step(in, kDt), TransitionReason::kNone);  // not from IDLE
  EXPECT_EQ(idle.state(), SafetyState::kIdle);

  SafetyStateMachine sm = running_machine();
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kJogRequested);
  EXPECT_EQ(sm.state(), SafetyState::kJog);
  EXPECT_TRUE(sm.outputs_enabled());
  in.jog_request = false;
  in.jog_end_request = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kJogEnded);
  EXPECT_EQ(sm.state(), SafetyState::kEnabling);  // back through the ramp
  in.jog_end_request = false;
  while (sm.state() == SafetyState::kEnabling) sm.step(in, kDt);
  EXPECT_EQ(sm.state(), SafetyState::kRunning);
}

TEST(SafetyStateMachine, JogYieldsToShutdownFaultsAndTheEstop) {
  SafetyInputs jog;
  jog.jog_request = true;
  SafetyStateMachine stop = running_machine();
  stop.step(jog, kDt);
  SafetyInputs in;
  in.shutdown_request = true;
  EXPECT_EQ(stop.step(in, kDt), TransitionReason::kShutdownRequested);
  EXPECT_EQ(stop.state(), SafetyState::kStopping);

  SafetyStateMachine fault = running_machine();
  fault.step(jog, kDt);
  in = {};
  in.bus_fault = true;
  EXPECT_EQ(fault.step(in, kDt), TransitionReason::kBusFault);

  SafetyStateMachine estop = running_machine();
  estop.step(jog, kDt);
  in = {};
  in.estop = true;
  EXPECT_EQ(estop.step(in, kDt), TransitionReason::kEstopInput);
  EXPECT_FALSE(estop.outputs_enabled());
}

TEST(SafetyStateMachine, EstopFromAnyStateLatchesUntilReleasedAndReset) {
  SafetyStateMachine sm = running_machine();
  SafetyInputs in;
  in.estop = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kEstopInput);
  EXPECT_EQ(sm.state(), SafetyState::kEstop);
  EXPECT_FALSE(sm.outputs_enabled());
  in.estop = false;
  sm.step(in, kDt);
  EXPECT_EQ(sm.state(), SafetyState::kEstop);  // released, not yet reset
  in.reset_request = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kFaultReset);
  EXPECT_EQ(sm.state(), SafetyState::kIdle);
}

TEST(SafetyStateMachine, BusFaultMeansFaultAndResetNeedsTheFaultCleared) {
  SafetyStateMachine sm = running_machine();
  SafetyInputs in;
  in.bus_fault = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kBusFault);
  EXPECT_EQ(sm.state(), SafetyState::kFault);
  in.reset_request = true;
  sm.step(in, kDt);
  EXPECT_EQ(sm.state(), SafetyState::kFault);
  in.bus_fault = false;
  sm.step(in, kDt);
  EXPECT_EQ(sm.state(), SafetyState::kIdle);
}

TEST(SafetyStateMachine, NConsecutiveOverrunsMeanFault) {
  SafetyParams p;
  p.overrun_fault_count = 5;
  SafetyStateMachine sm = running_machine(p);
  SafetyInputs in;
  for (int n = 1; n < 5; ++n) {
    in.consecutive_overruns = n;
    sm.step(in, kDt);
    EXPECT_EQ(sm.state(), SafetyState::kRunning) << n;
  }
  in.consecutive_overruns = 5;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kOverrunStorm);
}

TEST(SafetyStateMachine, RefusesToEnableOntoAnActuatorOutsideItsRange) {
  SafetyStateMachine sm({});
  SafetyInputs in;
  in.enable_request = true;
  in.feedback_out_of_range = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kFeedbackOutOfRange);
  EXPECT_EQ(sm.state(), SafetyState::kFault);
}

TEST(SafetyStateMachine, ALimitBreachOrFeedbackOutOfRangeWhileRunningMeansFault) {
  SafetyStateMachine sm = running_machine();
  SafetyInputs in;
  in.limit_breach = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kLimitBreach);
  SafetyStateMachine sm2 = running_machine();
  SafetyInputs in2;
  in2.feedback_out_of_range = true;
  EXPECT_EQ(sm2.step(in2, kDt), TransitionReason::kFeedbackOutOfRange);
}

TEST(SafetyStateMachine, AFaultDuringStoppingCutsOutputsAtOnce) {
  SafetyStateMachine sm = running_machine();
  SafetyInputs in;
  in.shutdown_request = true;
  sm.step(in, kDt);
  ASSERT_EQ(sm.state(), SafetyState::kStopping);
  in.bus_fault = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kBusFault);
  EXPECT_FALSE(sm.outputs_enabled());
}

TEST(SafetyStateMachine, ShutdownStopsAtRestOrOnTimeout) {
  SafetyParams p;
  p.stop_timeout_s = 0.1;
  SafetyStateMachine sm = running_machine(p);
  SafetyInputs in;
  in.shutdown_request = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kShutdownRequested);
  EXPECT_TRUE(sm.outputs_enabled());
  in.at_rest = true;
  EXPECT_EQ(sm.step(in, kDt), TransitionReason::kRestReached);
  EXPECT_EQ(sm.state(), SafetyState::kIdle);

  SafetyStateMachine sm2 = running_machine(p);
  in.at_rest = false;
  sm2.step(in, kDt);
  TransitionReason r = TransitionReason::kNone;
  for (int i = 0; i < 200 && r == TransitionReason::kNone; ++i) r = sm2.step(in, kDt);
  EXPECT_EQ(r, TransitionReason::kStopTimeout);
  EXPECT_EQ(sm2.state(), SafetyState::kIdle);
  // A shutdown request keeps it from enabling again.
  in.enable_request = true;
  sm2.step(in, kDt);
  EXPECT_EQ(sm2.state(), SafetyState::kIdle);
}

}  // namespace
}  // namespace facectl
