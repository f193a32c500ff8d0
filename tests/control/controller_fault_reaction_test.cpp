// FAULT with per-actuator reactions (docs/SAFETY.md, "Fault reaction") on the
// default head, whose rig is edited so that can0 carries hold and rest
// actuators (besides the jaw struts, which hold) and modbus0 only relax ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "control/mapping/mandible_mechanism.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/run/offline_head.hpp"
#include "tests/support/temp_file.hpp"
#include "tests/support/text_files.hpp"

namespace facectl {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::string default_rig_text() {
  return testing::read_text(testing::source_path("config/rigs/default.yaml"));
}

// Gives the actuator mapped from `signal` a fault reaction.
std::string with_reaction(const std::string& text, const std::string& signal,
                          const std::string& reaction) {
  const std::string map = "      map:\n        terms: { " + signal + "_deg: 1.0 }";
  return testing::replaced_once(text, map, "      fault_reaction: " + reaction + "\n" + map);
}

// can0: jaw struts hold (as shipped), neck_pan holds, neck_tilt and eye_yaw_l
// rest, the rest relax; modbus0: all relax.
std::string mixed_rig_text() {
  std::string t = with_reaction(default_rig_text(), "neck_pan", "hold");
  t = with_reaction(t, "neck_tilt", "rest");
  return with_reaction(t, "eye_yaw_l", "rest");
}

LoadedConfig load_rig(const std::string& text) {
  testing::TempFile file(text);
  ConfigOverrides o;
  o.rig_path = file.path();
  return load_config(default_config_path(), o);
}

class FaultReaction : public ::testing::Test {
 protected:
  void start(const std::string& rig_text) {
    head_ = std::make_unique<OfflineHead>(load_rig(rig_text), 0, true);
    const FaceLayout& layout = head_->model().layout;
    pose_ = head_->model().neutral;
    pose_[layout.jaw_pitch()] = 0.15;
    pose_[*layout.find("neck_tilt")] = 15 * kDeg;
    pose_[*layout.find("eye_yaw_l")] = 20 * kDeg;
    head_->controller().request_enable();
    run_sending(2.0);
    ASSERT_EQ(head_->controller().state(), SafetyState::kRunning);
  }

  void run_sending(double seconds) {
    const long n = std::lround(seconds / head_->period());
    for (long i = 0; i < n; ++i) {
      head_->send(pose_);
      head_->step(head_->period());
    }
  }

  std::size_t actuator(const std::string& name) const {
    const auto& a = head_->model().actuators;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].name == name) return i;
    }
    ADD_FAILURE() << name;
    return 0;
  }

  // The simulated plant of model actuator `a`.
  const sim::ServoPlant& plant(std::size_t a) {
    for (const BusModel& bus : head_->model().buses) {
      if (a >= bus.first && a < bus.first + bus.count) {
        return head_->hardware().find(bus.name)->plant(a - bus.first);
      }
    }
    ADD_FAILURE() << a;
    return head_->hardware().find("can0")->plant(0);
  }

  double command(std::size_t a) const { return head_->controller().commands()[a]; }

  face::MandiblePose jaw_pose() const {
    const MandibleMechanism& mech = *head_->model().mapping.mechanism;
    MandibleStrokes s{};
    for (std::size_t i = 0; i < mech.struts(); ++i) s[i] = command(mech.strut[i].actuator);
    const auto pose = forward(mech, s, head_->model().mandible_rest);
    EXPECT_TRUE(pose.has_value());
    return pose.value_or(face::MandiblePose{});
  }

  std::unique_ptr<OfflineHead> head_;
  std::array<double, kMaxFaceSignals> pose_{};
};

TEST_F(FaultReaction, BusFaultOnTheRelaxBusHoldsAndRestsTheOtherBus) {
  start(mixed_rig_text());
  const ControllerModel& m = head_->model();
  const double dt = head_->period();
  // Start fast moves, so the fault finds neck_pan and the jaw under way.
  pose_[*m.layout.find("neck_pan")] = 50 * kDeg;
  run_sending(0.1);
  pose_[m.layout.jaw_pitch()] = 0.3;
  run_sending(0.03);
  const std::size_t pan = actuator("neck_pan"), tilt = actuator("neck_tilt"),
                    eye = actuator("eye_yaw_l"), roll = actuator("neck_roll");
  const face::MandiblePose jaw_before = jaw_pose();

  head_->hardware().find("modbus0")->inject_fault("board 3 not answering");
  head_->send(pose_);
  head_->step(dt);
  ASSERT_EQ(head_->controller().state(), SafetyState::kFault);
  // Where the fault found the commands (this tick's, already sent).
  const LimiterState pan_at_fault = head_->controller().limiter(pan);
  ASSERT_GT(std::fabs(pan_at_fault.velocity), 30 * kDeg) << "neck_pan should be moving";
  const face::MandiblePose jaw_at_fault = jaw_pose();
  const double jaw_v = std::fabs(jaw_at_fault.pitch_rad - jaw_before.pitch_rad) / dt;
  ASSERT_GT(jaw_v, 0.2) << "the jaw should be moving";
  EXPECT_TRUE(head_->hardware().io.power_enabled()) << "some actuators hold or rest";
  EXPECT_TRUE(head_->hardware().find("can0")->enabled());
  EXPECT_FALSE(head_->hardware().find("modbus0")->enabled());
  for (const std::size_t a : {pan, tilt, eye}) EXPECT_TRUE(plant(a).enabled()) << a;
  EXPECT_FALSE(plant(roll).enabled()) << "neck_roll relaxes";
  const BusModel& modbus = m.buses[1];
  ASSERT_EQ(modbus.name, "modbus0");
  for (std::size_t a = modbus.first; a < modbus.first + modbus.count; ++a) {
    EXPECT_FALSE(plant(a).enabled()) << m.actuators[a].name;
  }

  // Two seconds in FAULT, input still arriving: every driven command keeps
  // its velocity and acceleration limits; relaxed ones show the measurement.
  std::array<double, kMaxActuators> prev = head_->controller().commands();
  std::array<double, kMaxActuators> prev_v{};
  double pan_travel = 0.0;
  for (int k = 0; k < 2000; ++k) {
    head_->send(pose_);
    head_->step(dt);
    ASSERT_EQ(head_->controller().state(), SafetyState::kFault);
    for (const std::size_t a : {pan, tilt, eye}) {
      const ActuatorLimits& l = m.actuators[a].limits;
      const double v = (command(a) - prev[a]) / dt;
      EXPECT_LE(std::fabs(v), l.max_velocity * (1 + 1e-9)) << m.actuators[a].name << " " << k;
      if (k > 0) {
        EXPECT_LE(std::fabs(v - prev_v[a]) / dt, l.max_acceleration * (1 + 1e-6) + 1e-6)
            << m.actuators[a].name << " " << k;
      }
      prev_v[a] = v;
    }
    pan_travel = std::max(pan_travel, std::fabs(command(pan) - pan_at_fault.position));
    EXPECT_EQ(command(roll), head_->controller().measured()[roll]);
    prev = head_->controller().commands();
  }
  // Hold: stopped within v²/2A + one tick of travel, and stays there.
  const ActuatorLimits& pl = m.actuators[pan].limits;
  const double v0 = std::fabs(pan_at_fault.velocity);
  EXPECT_LE(pan_travel, v0 * v0 / (2 * pl.max_acceleration) + v0 * dt + 1e-9);
  EXPECT_LT(std::fabs(head_->controller().limiter(pan).velocity), 1e-9);
  const double pan_stopped = command(pan);
  // Rest: reached under the limits checked above.
  EXPECT_NEAR(command(tilt), m.actuators[tilt].rest, 1e-6);
  EXPECT_NEAR(command(eye), m.actuators[eye].rest, 1e-6);
  EXPECT_GT(std::fabs(m.actuators[eye].rest - 20 * kDeg), 0.1) << "eye_yaw_l had to move";
  // The jaw's pose braked too: it moved on less than its pitch's stopping
  // distance from where the fault found it, and no longer moves.
  const face::MandiblePose jaw_held = jaw_pose();
  EXPECT_LE(std::fabs(jaw_held.pitch_rad - jaw_at_fault.pitch_rad),
            stopping_distance(m.mandible_limits[0], jaw_v, dt) + 1e-6);
  EXPECT_LT(jaw_held.pitch_rad, 0.3 - 1e-3) << "the jaw went on toward the live input";
  run_sending(0.5);
  EXPECT_NEAR(command(pan), pan_stopped, 1e-12);
  EXPECT_NEAR(jaw_pose().pitch_rad, jaw_held.pitch_rad, 1e-9);
  EXPECT_NEAR(plant(pan).position(), pan_stopped, 0.05 * kDeg) << "the neck itself holds";
  EXPECT_EQ(head_->hardware().find("modbus0")->writes_while_disabled(), 0u);

  // Reset after the bus recovers: IDLE, everything disabled, as today.
  head_->hardware().find("modbus0")->clear_fault();
  head_->controller().request_reset();
  run_sending(0.01);
  EXPECT_EQ(head_->controller().state(), SafetyState::kIdle);
  EXPECT_FALSE(head_->hardware().io.power_enabled());
  for (auto& bus : head_->hardware().buses) EXPECT_FALSE(bus->enabled());
}

// Forces `name`'s simulated servo toward `target` each tick, after the
// controller's own write (a hand or an obstacle pushing it, or a runaway).
void push(OfflineHead& head, const std::string& bus_name, std::size_t index, double target,
          double seconds, const std::array<double, kMaxFaceSignals>& pose) {
  SimActuatorBus& bus = *head.hardware().find(bus_name);
  const BusModel* model = nullptr;
  for (const BusModel& b : head.model().buses) {
    if (b.name == bus_name) model = &b;
  }
  ASSERT_NE(model, nullptr);
  const long n = std::lround(seconds / head.period());
  for (long i = 0; i < n; ++i) {
    head.send(pose);
    head.step(head.period());
    std::vector<double> cmd(head.controller().commands().begin() + model->first,
                            head.controller().commands().begin() + model->first + model->count);
    cmd[index - model->first] = target;
    bus.write({std::llround(head.time() * 1e9), head.period()}, cmd);
  }
}

TEST_F(FaultReaction, AnActuatorMeasuredOutsideItsRangeRelaxesInsteadOfHolding) {
  start(mixed_rig_text());
  const std::size_t neck = actuator("neck_pan");
  const double beyond = head_->model().actuators[neck].limits.position_max + 10 * kDeg;
  push(*head_, "can0", neck, beyond, 1.0, pose_);
  ASSERT_EQ(head_->controller().state(), SafetyState::kFault);
  EXPECT_FALSE(plant(neck).enabled()) << "a hold actuator found outside its range is not held";
  EXPECT_TRUE(plant(actuator("jaw_digastric")).enabled()) << "the jaw still holds";
  EXPECT_TRUE(head_->hardware().io.power_enabled());
}

TEST_F(FaultReaction, AHeldActuatorPushedOutOfItsRangeLaterRelaxesThen) {
  start(mixed_rig_text());
  head_->hardware().find("modbus0")->inject_fault("board 3 not answering");
  run_sending(0.1);
  ASSERT_EQ(head_->controller().state(), SafetyState::kFault);
  const std::size_t neck = actuator("neck_pan");
  ASSERT_TRUE(plant(neck).enabled());
  const double beyond = head_->model().actuators[neck].limits.position_max + 10 * kDeg;
  push(*head_, "can0", neck, beyond, 1.0, pose_);
  EXPECT_FALSE(plant(neck).enabled());
  EXPECT_TRUE(plant(actuator("jaw_digastric")).enabled());
}

TEST_F(FaultReaction, AFaultOnTheHoldBusItselfRelaxesIt) {
  start(mixed_rig_text());
  head_->hardware().find("can0")->inject_fault("bus-off");
  run_sending(0.01);
  EXPECT_EQ(head_->controller().state(), SafetyState::kFault);
  for (auto& bus : head_->hardware().buses) EXPECT_FALSE(bus->enabled()) << bus->name();
  EXPECT_FALSE(head_->hardware().io.power_enabled()) << "nothing holds or rests any more";
}

TEST_F(FaultReaction, TheHoldBusFaultingLaterRelaxesItThen) {
  start(mixed_rig_text());
  head_->hardware().find("modbus0")->inject_fault("board 3 not answering");
  run_sending(0.1);
  ASSERT_TRUE(head_->hardware().find("can0")->enabled());
  const std::uint64_t frames = head_->hardware().find("can0")->status().frames_sent;
  head_->hardware().find("can0")->inject_fault("bus-off");
  run_sending(0.1);
  EXPECT_EQ(head_->controller().state(), SafetyState::kFault);
  EXPECT_FALSE(head_->hardware().find("can0")->enabled());
  EXPECT_FALSE(head_->hardware().io.power_enabled());
  EXPECT_EQ(head_->hardware().find("can0")->status().frames_sent, frames);
  EXPECT_EQ(head_->hardware().find("can0")->writes_while_disabled(), 0u);
}

// A FAULT found after a stall: the stalled tick's long dt must not enter the
// held jaw's stopping distance, or "hold" becomes a sprint to a point far
// ahead (issue 19.1: 8 to 13 deg at up to 100 deg/s). A held axis brakes.
TEST_F(FaultReaction, AHeldJawBrakesAfterAStallWhateverTheStallsDt) {
  start(default_rig_text());
  const ControllerModel& m = head_->model();
  const double dt = head_->period();
  pose_[m.layout.jaw_pitch()] = 0.30;
  run_sending(0.02);
  head_->send(pose_);
  head_->step(0.2, 200);  // the stall, and the overruns it caused
  ASSERT_EQ(head_->controller().state(), SafetyState::kFault);
  face::MandiblePose before = jaw_pose();
  head_->step(dt);
  double speed = std::fabs(jaw_pose().pitch_rad - before.pitch_rad) / dt;
  ASSERT_GT(speed, 0.2) << "the jaw should still be moving when the fault is found";
  const double entry_speed = speed, entry_pitch = before.pitch_rad;
  double peak = 0.0;
  for (int i = 0; i < 500; ++i) {
    before = jaw_pose();
    head_->step(dt);
    speed = std::fabs(jaw_pose().pitch_rad - before.pitch_rad) / dt;
    peak = std::max(peak, speed);
  }
  EXPECT_LE(peak, entry_speed * 1.001) << "the held jaw sped up";
  EXPECT_LT(speed, 1e-9) << "the held jaw should have stopped";
  // Braking from the entry speed within the pose limits stops it within
  // v²/2A plus the jerk ramp: nowhere near v·0.2 s further on.
  const ActuatorLimits& l = m.mandible_limits[0];
  const double reach = stopping_distance(l, entry_speed, 2 * dt);
  EXPECT_LE(std::fabs(jaw_pose().pitch_rad - entry_pitch), reach)
      << "stopped " << (jaw_pose().pitch_rad - entry_pitch) / kDeg << " deg on";
}

TEST_F(FaultReaction, EstopCutsEverythingWhateverTheReactions) {
  start(mixed_rig_text());
  head_->hardware().io.press_estop();
  run_sending(head_->period());
  EXPECT_EQ(head_->controller().state(), SafetyState::kEstop);
  EXPECT_FALSE(head_->hardware().io.power_enabled());
  for (auto& bus : head_->hardware().buses) EXPECT_FALSE(bus->enabled());
}

TEST_F(FaultReaction, EstopDuringAHoldingFaultCutsEverything) {
  start(mixed_rig_text());
  head_->hardware().find("modbus0")->inject_fault("board 3 not answering");
  run_sending(0.05);
  ASSERT_TRUE(head_->hardware().io.power_enabled());
  head_->hardware().io.press_estop();
  run_sending(head_->period());
  EXPECT_EQ(head_->controller().state(), SafetyState::kEstop);
  EXPECT_FALSE(head_->hardware().io.power_enabled());
  for (auto& bus : head_->hardware().buses) EXPECT_FALSE(bus->enabled());
}

TEST_F(FaultReaction, AnAllRelaxRigCutsEverythingAsBefore) {
  // The three jaw struts are the shipped rig's only holding actuators.
  start(testing::replaced_all(default_rig_text(), "fault_reaction: hold", "fault_reaction: relax",
                              3));
  head_->hardware().find("modbus0")->inject_fault("board 3 not answering");
  head_->step(head_->period());
  EXPECT_EQ(head_->controller().state(), SafetyState::kFault);
  EXPECT_FALSE(head_->hardware().io.power_enabled());
  for (auto& bus : head_->hardware().buses) EXPECT_FALSE(bus->enabled());
  std::uint64_t frames = 0;
  for (auto* bus : head_->hardware().seams) frames += bus->status().frames_sent;
  run_sending(0.2);
  std::uint64_t after = 0;
  for (auto* bus : head_->hardware().seams) after += bus->status().frames_sent;
  EXPECT_EQ(after, frames);
  for (std::size_t a = 0; a < head_->model().actuators.size(); ++a) {
    EXPECT_EQ(command(a), head_->controller().measured()[a]) << "telemetry shows the measurement";
  }
}

TEST(FaultReactionConfig, StrutsOfMixedReactionsAreRefusedNamingTheLine) {
  // The second strut (jaw_pterygoid_l) relaxes while the others hold.
  std::string t = default_rig_text();
  const std::size_t second = t.find("fault_reaction: hold", t.find("name: jaw_pterygoid_l"));
  ASSERT_NE(second, std::string::npos);
  t.replace(second, std::string("fault_reaction: hold").size(), "fault_reaction: relax");
  const long line = std::count(t.begin(), t.begin() + static_cast<long>(second), '\n') + 1;
  std::string error;
  try {
    load_rig(t);
  } catch (const ConfigError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find(":" + std::to_string(line) + ":"), std::string::npos) << error;
  EXPECT_NE(error.find("'jaw_pterygoid_l'.fault_reaction"), std::string::npos) << error;
  EXPECT_NE(error.find("found relax"), std::string::npos) << error;
}

}  // namespace
}  // namespace facectl
