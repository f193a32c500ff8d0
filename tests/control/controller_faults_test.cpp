// Fault scenarios on the default head in simulated time. Each ends in the
// safe state docs/SAFETY.md documents, within the time it documents.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/support/sim_head.hpp"

namespace facectl {
namespace {

using testing::SimHead;

class ControllerFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    pose_ = head_.model().neutral;
    for (const auto& [name, value] :
         {std::pair{"zygomaticus_major_l", 0.8}, std::pair{"zygomaticus_major_r", 0.8},
          std::pair{"frontalis_inner_l", 0.6}}) {
      pose_[*head_.model().layout.find(name)] = value;
    }
    pose_[head_.model().layout.jaw_pitch()] = 0.15;
    head_.controller().request_enable();
    run_sending(2.0);
    ASSERT_EQ(head_.controller().state(), SafetyState::kRunning);
  }

  void run_sending(double seconds) {
    const long n = std::lround(seconds / head_.period());
    for (long i = 0; i < n; ++i) {
      head_.send(pose_);
      head_.step(head_.period());
    }
  }

  std::uint64_t frames_sent() {
    std::uint64_t n = 0;
    for (auto* bus : head_.hardware().seams) n += bus->status().frames_sent;
    return n;
  }

  TransitionEvent last_event() {
    TransitionEvent ev;
    while (const TransitionEvent* e = head_.events().front()) {
      ev = *e;
      head_.events().pop();
    }
    return ev;
  }

  // A small distance in an actuator's own unit: 0.05 deg or 0.05 mm.
  double small(std::size_t a) const {
    return head_.model().actuators[a].kind == ActuatorKind::kRotary ? 0.05 * 3.14159265 / 180.0
                                                                    : 0.05e-3;
  }

  SimHead head_{default_config_path(), 0, true};
  std::array<double, kMaxFaceSignals> pose_{};
};

TEST_F(ControllerFaults, InputTimeoutEasesToNeutralWithinTheDocumentedTime) {
  const ControllerModel& m = head_.model();
  std::array<double, kMaxActuators> neutral_targets{};
  MappingWorkspace w = make_mapping_workspace(m.mapping);
  map_to_actuators(m.mapping, w, m.neutral, neutral_targets);
  // The input stops. Documented bound: timeout + neutral ease + 0.5 s to settle.
  const double bound = m.safety.input_timeout_s + m.shaping.neutral_ease_time_s + 0.5;
  double stale_at = -1.0;
  const double t0 = head_.time();
  while (head_.time() - t0 < bound) {
    head_.step(head_.period());
    if (stale_at < 0 && head_.controller().input_stale()) stale_at = head_.time() - t0;
  }
  EXPECT_NEAR(stale_at, m.safety.input_timeout_s, 2 * head_.period());
  EXPECT_EQ(head_.controller().state(), SafetyState::kRunning);
  for (std::size_t a = 0; a < m.actuators.size(); ++a) {
    EXPECT_NEAR(head_.controller().commands()[a], neutral_targets[a], small(a))
        << m.actuators[a].name;
  }
  // Input comes back: the face follows it again.
  run_sending(1.0);
  EXPECT_FALSE(head_.controller().input_stale());
  EXPECT_NEAR(head_.controller().face()[m.layout.jaw_pitch()], 0.15, 1e-3);
}

TEST_F(ControllerFaults, EstopEdgeStopsTransmissionOnTheTickItIsRead) {
  head_.hardware().io.press_estop();
  const std::uint64_t before = frames_sent();
  head_.send(pose_);
  head_.step(head_.period());  // the tick that reads the edge
  EXPECT_EQ(head_.controller().state(), SafetyState::kEstop);
  EXPECT_FALSE(head_.hardware().io.power_enabled());
  for (auto& bus : head_.hardware().buses) EXPECT_FALSE(bus->enabled());
  run_sending(0.5);
  EXPECT_EQ(frames_sent(), before) << "a command was transmitted in ESTOP";
  for (auto& bus : head_.hardware().buses) EXPECT_EQ(bus->writes_while_disabled(), 0u);
  EXPECT_EQ(last_event().reason, TransitionReason::kEstopInput);
  // Released but not reset: still ESTOP.
  head_.hardware().io.release_estop();
  run_sending(0.1);
  EXPECT_EQ(head_.controller().state(), SafetyState::kEstop);
  head_.controller().request_reset();
  run_sending(0.01);
  EXPECT_EQ(head_.controller().state(), SafetyState::kIdle);
}

TEST_F(ControllerFaults, BusFaultDisablesItsBusOnTheNextTickWithItsReason) {
  // The default rig's jaw struts hold (docs/SAFETY.md, "Fault reaction"):
  // can0 stays on for them, everything else relaxes.
  head_.hardware().find("modbus0")->inject_fault("board 3 not answering");
  head_.step(head_.period());
  EXPECT_EQ(head_.controller().state(), SafetyState::kFault);
  EXPECT_TRUE(head_.hardware().io.power_enabled());
  EXPECT_FALSE(head_.hardware().find("modbus0")->enabled());
  EXPECT_TRUE(head_.hardware().find("can0")->enabled());
  const ControllerModel& m = head_.model();
  const BusModel& can = m.buses[0];
  ASSERT_EQ(can.name, "can0");
  for (std::size_t a = can.first; a < can.first + can.count; ++a) {
    EXPECT_EQ(head_.hardware().find("can0")->plant(a - can.first).enabled(),
              m.actuators[a].fault_reaction != FaultReaction::kRelax)
        << m.actuators[a].name;
  }
  const TransitionEvent ev = last_event();
  EXPECT_EQ(ev.reason, TransitionReason::kBusFault);
  EXPECT_STREQ(ev.detail, "board 3 not answering");
  const std::uint64_t before = head_.hardware().find("modbus0")->status().frames_sent;
  run_sending(0.2);
  EXPECT_EQ(head_.hardware().find("modbus0")->status().frames_sent, before);
  EXPECT_EQ(head_.hardware().find("modbus0")->writes_while_disabled(), 0u);
}

TEST_F(ControllerFaults, OverrunStormFaultsAfterTheConfiguredCount) {
  const int n = head_.model().safety.overrun_fault_count;
  for (int i = 1; i < n; ++i) {
    head_.step(head_.period(), i);
    ASSERT_EQ(head_.controller().state(), SafetyState::kRunning) << i;
  }
  head_.step(head_.period(), n);
  EXPECT_EQ(head_.controller().state(), SafetyState::kFault);
  EXPECT_EQ(last_event().reason, TransitionReason::kOverrunStorm);
}

TEST_F(ControllerFaults, ShutdownEasesToRestThenDisables) {
  const ControllerModel& m = head_.model();
  head_.controller().request_shutdown();
  double t = 0.0;
  while (head_.controller().state() != SafetyState::kIdle && t < m.safety.stop_timeout_s + 0.1) {
    head_.send(pose_);
    head_.step(head_.period());
    t += head_.period();
  }
  EXPECT_EQ(head_.controller().state(), SafetyState::kIdle);
  EXPECT_LT(t, m.safety.stop_timeout_s) << "rest was not reached before the timeout";
  EXPECT_EQ(last_event().reason, TransitionReason::kRestReached);
  for (std::size_t a = 0; a < m.actuators.size(); ++a) {
    const ActuatorLimits& l = m.actuators[a].limits;
    EXPECT_NEAR(head_.controller().limiter(a).position, m.actuators[a].rest,
                m.rest_tolerance_fraction * (l.soft_max - l.soft_min) + 1e-12);
    // The actuator itself, not only its command, is at rest when outputs drop.
    const sim::ServoPlant* plant = nullptr;
    for (auto& bus : head_.hardware().buses) {
      for (std::size_t b = 0; b < m.buses.size(); ++b) {
        if (m.buses[b].name == bus->name() && a >= m.buses[b].first &&
            a < m.buses[b].first + m.buses[b].count) {
          plant = &bus->plant(a - m.buses[b].first);
        }
      }
    }
    ASSERT_NE(plant, nullptr);
    EXPECT_NEAR(plant->position(), m.actuators[a].rest,
                m.rest_measured_tolerance_fraction * (l.soft_max - l.soft_min))
        << m.actuators[a].name;
  }
  EXPECT_FALSE(head_.hardware().io.power_enabled());
}

TEST_F(ControllerFaults, ReEnableIsBumplessFromWhereTheActuatorsStopped) {
  const ControllerModel& m = head_.model();
  // E-stop in the middle of a fast jaw move, so commands are still in flight.
  pose_[m.layout.jaw_pitch()] = 0.3;
  run_sending(0.03);
  head_.hardware().io.press_estop();
  run_sending(0.2);
  head_.hardware().io.release_estop();
  head_.controller().request_reset();
  run_sending(0.01);
  ASSERT_EQ(head_.controller().state(), SafetyState::kIdle);

  auto plant_positions = [&] {
    std::vector<double> p;
    for (auto& bus : head_.hardware().buses) {
      for (std::size_t i = 0; i < m.buses.size(); ++i) {
        if (m.buses[i].name != bus->name()) continue;
        for (std::size_t k = 0; k < m.buses[i].count; ++k) p.push_back(bus->plant(k).position());
      }
    }
    return p;  // in model (bus) order, as m.buses lists them
  };
  const std::vector<double> before = plant_positions();
  head_.controller().request_enable();
  run_sending(head_.period());
  const auto seed = head_.controller().commands();  // the measured positions, noise included
  const double window = 0.003;                      // longer than the 2 ms plant latency
  run_sending(window - head_.period());
  ASSERT_EQ(head_.controller().state(), SafetyState::kEnabling);
  const std::vector<double> after = plant_positions();
  for (std::size_t a = 0; a < m.actuators.size(); ++a) {
    // From standstill no actuator may move further than its acceleration
    // limit allows in the window: no jump toward a pre-e-stop target.
    // (The seed is the measured position, so its noise is allowed for.)
    const double allowed = 0.5 * m.actuators[a].limits.max_acceleration * window * window +
                           std::fabs(seed[a] - before[a]);
    EXPECT_LE(std::fabs(after[a] - before[a]), allowed + 1e-12) << m.actuators[a].name;
  }
}

TEST_F(ControllerFaults, EnablingOntoAnActuatorBeyondItsRangeFaults) {
  head_.controller().request_shutdown();
  run_sending(3.0);
  ASSERT_EQ(head_.controller().state(), SafetyState::kIdle);
  // A new controller on hardware whose jaw was pushed past its hardware range.
  SimHead other;
  // Drive the simulated jaw beyond its range by enabling the plant directly.
  auto& bus = *other.hardware().find("can0");
  bus.set_enabled(true);
  const double beyond = other.model().actuators[0].limits.position_max + 0.05;
  std::vector<double> cmd(other.model().buses[0].count, 0.0);
  std::vector<double> seen(cmd.size(), 0.0);
  cmd[0] = beyond;
  for (int i = 0; i < 2000; ++i) {
    bus.write({static_cast<std::int64_t>(i) * 1'000'000, 0.001}, cmd);
    bus.read({static_cast<std::int64_t>(i) * 1'000'000, 0.001}, seen);
  }
  ASSERT_GT(bus.plant(0).position(), other.model().actuators[0].limits.position_max);
  bus.set_enabled(false);
  other.controller().request_enable();
  other.step(other.period());
  other.step(other.period());
  EXPECT_EQ(other.controller().state(), SafetyState::kFault);
  EXPECT_FALSE(other.hardware().io.power_enabled());
}

}  // namespace
}  // namespace facectl
