// The operations of `facectl serve` on the default head, simulated hardware:
// each one goes through the safety state machine, an e-stop or a fault is
// never bypassed, and every command and transition lands in the event log.
#include "firmware-host/serve/head_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "tests/firmware-host/serve/served_head.hpp"

namespace facectl {
namespace {

using testing::ServedHead;

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(HeadService, StartsIdleEnablesToRunningAndDisablesToIdle) {
  ServedHead h;
  EXPECT_EQ(h.service().state(), SafetyState::kIdle);
  EXPECT_EQ(h.service().enable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  EXPECT_EQ(h.service().disable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kIdle));
}

TEST(HeadService, ResetIsRefusedWhileTheEstopIsPressedThenReEnables) {
  ServedHead h;
  SimHardware& sim = *h.session().head.sim;
  ASSERT_EQ(h.service().enable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  sim.io.press_estop();
  ASSERT_TRUE(h.wait_for(SafetyState::kEstop));

  // Neither enable nor reset gets past a pressed e-stop.
  const HeadService::Result enable = h.service().enable("test");
  EXPECT_EQ(enable.status, 409);
  EXPECT_NE(enable.error.find("reset"), std::string::npos) << enable.error;
  const HeadService::Result pressed = h.service().reset("test", true);
  EXPECT_EQ(pressed.status, 409);
  EXPECT_NE(pressed.error.find("e-stop is still pressed"), std::string::npos) << pressed.error;
  EXPECT_EQ(h.service().state(), SafetyState::kEstop);
  EXPECT_FALSE(sim.io.power_enabled());

  sim.io.release_estop();
  EXPECT_EQ(h.service().reset("test", true).status, 200);
  // Re-enabled through ENABLING, the bumpless ramp from the measured positions.
  ASSERT_TRUE(h.wait_for(SafetyState::kEnabling, 1.0));
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
}

TEST(HeadService, AFaultIsResetOnlyOnceItsCauseIsGone) {
  ServedHead h;
  SimHardware& sim = *h.session().head.sim;
  ASSERT_EQ(h.service().enable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  sim.io.inject_fault(true);  // the safety I/O reports a fault
  ASSERT_TRUE(h.wait_for(SafetyState::kFault));
  ASSERT_TRUE(testing::wait_until(
      [&] { return h.service().active_fault()->reason == "safety I/O fault"; }, 1.0));
  EXPECT_EQ(h.service().active_fault()->state, "FAULT");

  const HeadService::Result still = h.service().reset("test", true);
  EXPECT_EQ(still.status, 409);
  EXPECT_NE(still.error.find("cause is still present"), std::string::npos) << still.error;

  sim.io.inject_fault(false);
  const HeadService::Result reset = h.service().reset("test", false);
  EXPECT_EQ(reset.status, 200) << reset.error;
  ASSERT_TRUE(h.wait_for(SafetyState::kIdle));
  EXPECT_FALSE(h.service().active_fault().has_value());
  // {"enable": false}: stays IDLE.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(h.service().state(), SafetyState::kIdle);
}

TEST(HeadService, ResetWithNothingToResetIsRefused) {
  ServedHead h;
  EXPECT_EQ(h.service().reset("test", true).status, 409);
  EXPECT_EQ(h.service().state(), SafetyState::kIdle);
}

TEST(HeadService, UnknownAndBrokenShowsAreRefusedAndTheSourceStays) {
  ServedHead h;
  h.shows().write("broken.yaml",
                  "show:\n  name: broken\n  keyframes:\n    - { t: 0, expression: nope }\n");
  ASSERT_EQ(h.service().hold_expression("test", "joy", 0.5).status, 200);

  EXPECT_EQ(h.service().play("test", "absent", false).status, 404);
  EXPECT_EQ(h.service().play("test", "../shows/demo", false).status, 404);
  const HeadService::Result broken = h.service().play("test", "broken", false);
  EXPECT_EQ(broken.status, 422);
  EXPECT_NE(broken.error.find("broken.yaml"), std::string::npos) << broken.error;
  EXPECT_EQ(h.service().hold_expression("test", "nope", 1.0).status, 404);

  const FaceDirector::Status st = h.service().director().status();
  EXPECT_EQ(st.source, FaceDirector::Source::kExpression);
  EXPECT_EQ(st.name, "joy");
  EXPECT_EQ(h.service().state(), SafetyState::kIdle);  // nothing enabled
}

TEST(HeadService, PlaysQueuesAndStopsShowsByName) {
  ServedHead h;
  ASSERT_EQ(h.service().play("test", "demo", false).status, 200);
  ASSERT_EQ(h.service().play("test", "demo", true).status, 200);
  FaceDirector::Status st = h.service().director().status();
  EXPECT_EQ(st.source, FaceDirector::Source::kShow);
  EXPECT_EQ(st.name, "demo");
  EXPECT_DOUBLE_EQ(st.duration_s, 13.0);
  ASSERT_EQ(st.queue.size(), 1u);
  EXPECT_EQ(h.service().stop_show("test").status, 200);
  st = h.service().director().status();
  EXPECT_EQ(st.source, FaceDirector::Source::kNeutral);
  EXPECT_TRUE(st.queue.empty());
}

TEST(HeadService, TheEventLogHoldsEachCommandAndTransitionWithItsSource) {
  ServedHead h;
  ASSERT_EQ(h.service().enable("api 127.0.0.1").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  ASSERT_EQ(h.service().disable("api 127.0.0.1").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kIdle));
  ASSERT_TRUE(testing::wait_until(
      [&] { return read_all(h.log_path()).find("STOPPING -> IDLE") != std::string::npos; }, 2.0));
  const std::string log = read_all(h.log_path());
  for (const char* expected : {R"("kind":"command","source":"api 127.0.0.1","text":"enable")",
                               R"("text":"IDLE -> ENABLING: enable requested")",
                               R"("text":"ENABLING -> RUNNING: enable ramp complete")",
                               R"("kind":"command","source":"api 127.0.0.1","text":"disable")",
                               R"("text":"RUNNING -> STOPPING: shutdown requested")"}) {
    EXPECT_NE(log.find(expected), std::string::npos) << expected << "\n" << log;
  }
}

std::size_t actuator_index(const ControllerModel& m, const std::string& name) {
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    if (m.actuators[i].name == name) return i;
  }
  throw std::out_of_range(name);
}

TEST(HeadService, JogMovesOneActuatorAtTheCappedSpeedWhileTheOthersHold) {
  ServedHead h;
  const ControllerModel& m = h.session().head.model();
  const std::size_t pan = actuator_index(m, "neck_pan");
  const double cap = m.safety.jog_speed_fraction * m.actuators[pan].limits.max_velocity;

  EXPECT_EQ(h.service().jog_start("test").status, 409);  // not from IDLE
  EXPECT_EQ(h.service().jog("test", "neck_pan", 10).status, 409);
  ASSERT_EQ(h.service().enable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  ASSERT_EQ(h.service().jog_start("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kJog));

  EXPECT_EQ(h.service().jog("test", "nope", 0).status, 404);
  EXPECT_EQ(h.service().jog("test", "jaw_digastric", 0).status, 409);  // a strut
  const HeadService::Result far = h.service().jog("test", "neck_pan", 61);
  EXPECT_EQ(far.status, 422);
  EXPECT_NE(far.error.find("expected -60..60"), std::string::npos) << far.error;

  TelemetryRecord start;
  ASSERT_TRUE(testing::wait_until([&] { return h.service().latest(start) > 0; }, 1.0));
  // The face input is ignored in JOG: a new source moves nothing.
  ASSERT_EQ(h.service().hold_expression("test", "joy", 1.0).status, 200);
  ASSERT_EQ(h.service().jog("test", "neck_pan", 20).status, 200);
  const double goal = 20.0 * M_PI / 180.0;
  TelemetryRecord prev = start;
  double fastest = 0.0;
  double others_moved = 0.0;  // the largest move of an actuator not jogged
  ASSERT_TRUE(testing::wait_until(
      [&] {
        TelemetryRecord rec;
        h.service().latest(rec);
        if (rec.tick > prev.tick) {
          fastest = std::max(
              fastest, std::abs(rec.command[pan] - prev.command[pan]) / (rec.time_s - prev.time_s));
          for (std::size_t i = 0; i < m.actuators.size(); ++i) {
            if (i != pan) {
              others_moved = std::max(others_moved, std::abs(rec.command[i] - start.command[i]));
            }
          }
          prev = rec;
        }
        return std::abs(rec.command[pan] - goal) < 1e-6;
      },
      10.0))
      << "neck_pan at " << prev.command[pan] << " rad, goal " << goal;
  EXPECT_LE(fastest, cap * 1.001);
  EXPECT_GT(fastest, cap * 0.5);
  // Held: what is left is the limiters braking a residual velocity from
  // before JOG (nanometres, nanoradians); joy would move the face servos by
  // degrees and millimetres.
  EXPECT_LT(others_moved, 1e-6);

  ASSERT_EQ(h.service().jog_stop("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));  // through the ramp
}

// Enabled and in JOG, or the test fails.
void start_jog(ServedHead& h) {
  ASSERT_EQ(h.service().enable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  ASSERT_EQ(h.service().jog_start("test").status, 200);
  ASSERT_EQ(h.service().state(), SafetyState::kJog);  // answered once the tick took it
}

TEST(HeadService, JogStaysWhereSomeAdmissibleFaceTakesTheActuator) {
  ServedHead h;
  const ControllerModel& m = h.session().head.model();
  const std::size_t corner = actuator_index(m, "lip_pucker");
  // Soft range -40..40 deg, but no admissible face takes the pucker servo below 0.
  EXPECT_NEAR(h.service().jog_ranges()[corner].lo, 0.0, 1e-6);
  EXPECT_NEAR(h.service().jog_ranges()[corner].hi, 35.0, 1e-6);
  start_jog(h);
  const HeadService::Result low = h.service().jog("test", "lip_pucker", -10);
  EXPECT_EQ(low.status, 422);
  EXPECT_NE(low.error.find("expected 0..35"), std::string::npos) << low.error;
  EXPECT_EQ(h.service().jog("test", "lip_pucker", 20).status, 200);
}

TEST(HeadService, JoggingAnotherActuatorStopsTheFirstWhereItIs) {
  ServedHead h;
  const ControllerModel& m = h.session().head.model();
  const std::size_t pan = actuator_index(m, "neck_pan");
  start_jog(h);
  ASSERT_EQ(h.service().jog("test", "neck_pan", 60).status, 200);  // 5 s at the jog speed
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(h.service().jog("test", "neck_tilt", 5).status, 200);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  TelemetryRecord a;
  h.service().latest(a);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  TelemetryRecord b;
  h.service().latest(b);
  EXPECT_LT(a.command[pan], 30.0 * M_PI / 180.0);     // far from its old target
  EXPECT_NEAR(b.command[pan], a.command[pan], 1e-9);  // and still
}

TEST(HeadService, LeavingJogRampsBackToTheFaceInput) {
  ServedHead h;
  start_jog(h);
  ASSERT_EQ(h.service().jog_stop("test").status, 200);
  EXPECT_EQ(h.service().state(), SafetyState::kEnabling);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
}

TEST(HeadService, OnceStoppingNothingCanMoveTheHeadAgain) {
  ServedHead h;
  ASSERT_EQ(h.service().enable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  h.service().begin_shutdown("signal 15");
  for (const HeadService::Result& r :
       {h.service().enable("test"), h.service().reset("test", true), h.service().jog_start("test"),
        h.service().play("test", "demo", false), h.service().hold_expression("test", "joy", 1.0)}) {
    EXPECT_EQ(r.status, 503) << r.error;
  }
  EXPECT_EQ(h.service().disable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kIdle));
}

TEST(HeadService, TheEstopEndsAJog) {
  ServedHead h;
  ASSERT_EQ(h.service().enable("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kRunning));
  ASSERT_EQ(h.service().jog_start("test").status, 200);
  ASSERT_TRUE(h.wait_for(SafetyState::kJog));
  ASSERT_EQ(h.service().jog("test", "neck_pan", 30).status, 200);
  h.session().head.sim->io.press_estop();
  ASSERT_TRUE(h.wait_for(SafetyState::kEstop));
  EXPECT_FALSE(h.session().head.sim->io.power_enabled());
  EXPECT_EQ(h.service().jog("test", "neck_pan", 0).status, 409);
}

TEST(EventLog, RotatesBySizeAndKeepsTheNewestFiles) {
  testing::TempDir dir;
  const std::string path = dir.file("events.jsonl");
  {
    EventLog log(path, 1024, 2);
    for (int i = 0; i < 60; ++i) log.add("command", "test", "entry " + std::to_string(i));
    EXPECT_EQ(log.write_errors(), 0u);
    ASSERT_EQ(log.recent(5).size(), 5u);
    EXPECT_EQ(log.recent(5).back().text, "entry 59");
  }
  EXPECT_TRUE(std::filesystem::exists(path + ".1"));
  EXPECT_TRUE(std::filesystem::exists(path + ".2"));
  EXPECT_FALSE(std::filesystem::exists(path + ".3"));
  EXPECT_LE(std::filesystem::file_size(path), 1024u);
  EXPECT_NE(read_all(path).find("entry 59"), std::string::npos);
  // Reopened after a restart: appended, not truncated.
  EventLog again(path, 1 << 20, 2);
  again.add("service", "test", "restarted");
  const std::string text = read_all(path);
  EXPECT_NE(text.find("entry 59"), std::string::npos);
  EXPECT_NE(text.find("restarted"), std::string::npos);
}

}  // namespace
}  // namespace facectl
