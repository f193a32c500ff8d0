// Drive-level protection in the controller (docs/SAFETY.md, "Drive-level
// protection") on the hobby DYNAMIXEL rig, whose actuators derate from 60 °C
// and fault at 70 °C: scripted health through the simulated bus, and the
// simulated servo's own thermal model when it is stalled against an obstacle.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/run/offline_head.hpp"
#include "tests/support/temp_file.hpp"
#include "tests/support/text_files.hpp"

namespace facectl {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::string rig_text() {
  return testing::read_text(testing::source_path("config/rigs/hobby_dynamixel.yaml"));
}

LoadedConfig load_rig(const std::string& text) {
  testing::TempFile file(text);
  ConfigOverrides o;
  o.rig_path = file.path();
  return load_config(default_config_path(), o);
}

class ControllerProtection : public ::testing::Test {
 protected:
  void start(const std::string& text = rig_text()) {
    head_ = std::make_unique<OfflineHead>(load_rig(text), 1 << 12, true);
    pose_ = head_->model().neutral;
    head_->controller().request_enable();
    run(2.0);
    ASSERT_EQ(head_->controller().state(), SafetyState::kRunning);
  }

  void look(double yaw_deg) {
    const FaceLayout& layout = head_->model().layout;
    pose_[*layout.find("eye_yaw_l")] = yaw_deg * kDeg;
    pose_[*layout.find("eye_yaw_r")] = yaw_deg * kDeg;
  }

  // Runs while sending the pose; stops early on FAULT if asked.
  void run(double seconds, bool until_fault = false) {
    const long n = std::lround(seconds / head_->period());
    for (long i = 0; i < n; ++i) {
      head_->send(pose_);
      head_->step(head_->period());
      drain_telemetry();
      if (until_fault && head_->controller().state() == SafetyState::kFault) return;
    }
  }

  void drain_telemetry() {
    auto* ring = head_->telemetry();
    while (const TelemetryRecord* r = ring->front()) {
      last_ = *r;
      ring->pop();
    }
  }

  std::string last_event_detail() {
    std::string detail;
    while (const TransitionEvent* e = head_->events().front()) {
      if (e->reason == TransitionReason::kDriveProtection) detail = e->detail;
      head_->events().pop();
    }
    return detail;
  }

  std::size_t actuator(const std::string& name) const {
    const auto& a = head_->model().actuators;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].name == name) return i;
    }
    ADD_FAILURE() << name;
    return 0;
  }

  SimActuatorBus& bus() { return *head_->hardware().find("servos"); }
  double command_deg(std::size_t a) const { return head_->controller().commands()[a] / kDeg; }

  std::unique_ptr<OfflineHead> head_;
  std::array<double, kMaxFaceSignals> pose_{};
  TelemetryRecord last_{};
};

TEST_F(ControllerProtection, TemperatureDeratesTowardRestThenFaultsNamingTheActuator) {
  start();
  const std::size_t pan = actuator("eyes_pan"), lid = actuator("lid_l");
  look(25.0);
  run(1.0);
  ASSERT_NEAR(command_deg(pan), 25.0, 0.1);
  ActuatorHealth hot;
  hot.temperature_c = 65.0;  // half way from 60 to 70: factor 0.75 (floor 0.5)
  bus().script_health(pan, hot);
  run(0.05);
  EXPECT_NEAR(command_deg(pan), 25.0, 0.1) << "not before the hold time";
  run(1.0);
  EXPECT_EQ(head_->controller().state(), SafetyState::kRunning);
  EXPECT_NEAR(command_deg(pan), 0.75 * 25.0, 0.1) << "pulled toward rest (0 deg)";
  EXPECT_NEAR(head_->controller().protection(pan).factor, 0.75, 1e-9);
  // In telemetry too.
  ASSERT_NE(last_.protected_mask & (std::uint64_t{1} << pan), 0u);
  EXPECT_FLOAT_EQ(last_.temperature_c[pan], 65.0f);
  EXPECT_FLOAT_EQ(last_.derate[pan], 0.75f);
  EXPECT_EQ(last_.protection[pan], static_cast<std::uint8_t>(ProtectionMode::kDerating));

  hot.temperature_c = 70.5;
  bus().script_health(pan, hot);
  run(0.099, true);
  EXPECT_EQ(head_->controller().state(), SafetyState::kRunning);
  run(0.01, true);
  ASSERT_EQ(head_->controller().state(), SafetyState::kFault);
  EXPECT_EQ(last_event_detail(),
            "drive protection: eyes_pan temperature >= 70 C for 100 ms, read 70.5");
  // eyes_pan relaxes (its reaction), lid_l holds (its reaction).
  EXPECT_FALSE(bus().plant(pan).enabled());
  EXPECT_TRUE(bus().plant(lid).enabled());

  // Reset is refused while it is still hot, accepted once it has cooled.
  head_->controller().request_reset();
  run(0.01);
  EXPECT_EQ(head_->controller().state(), SafetyState::kFault);
  hot.temperature_c = 50.0;
  bus().script_health(pan, hot);
  head_->controller().request_reset();
  run(0.01);
  EXPECT_EQ(head_->controller().state(), SafetyState::kIdle);
}

TEST_F(ControllerProtection, HardwareErrorFaultsAtOnceAndRelaxesThatActuatorOnly) {
  start();
  const std::size_t lid_l = actuator("lid_l"), lid_r = actuator("lid_r"), jaw = actuator("jaw");
  ActuatorHealth h;
  h.hardware_error = 1u << 5;  // overload
  bus().script_health(lid_l, h);
  run(head_->period(), true);
  ASSERT_EQ(head_->controller().state(), SafetyState::kFault);
  EXPECT_EQ(last_event_detail(),
            "drive protection: lid_l hardware_error bit set, mask 4294967295, read 32.0");
  // lid_l would hold, but its servo switched itself off: it relaxes. lid_r
  // holds and the jaw goes to rest, as their reactions say.
  EXPECT_FALSE(bus().plant(lid_l).enabled());
  EXPECT_TRUE(bus().plant(lid_r).enabled());
  EXPECT_TRUE(bus().plant(jaw).enabled());
  run(1.0);
  EXPECT_NEAR(command_deg(jaw), head_->model().actuators[jaw].rest / kDeg, 0.1);
}

TEST_F(ControllerProtection, UnreportedValuesNeitherDerateNorFault) {
  // The simulated servos report no voltage (NaN) although the rig limits it,
  // and a cool temperature: nothing derates, nothing faults.
  start();
  look(20.0);
  run(3.0);
  EXPECT_EQ(head_->controller().state(), SafetyState::kRunning);
  for (std::size_t i = 0; i < head_->model().actuators.size(); ++i) {
    EXPECT_EQ(head_->controller().protection(i).factor, 1.0) << i;
  }
}

// eyes_pan with a thermal model ten times faster than the default (6 s), so
// that a stall heats it in seconds, not minutes.
std::string fast_thermal_rig() {
  return testing::replaced_once(
      rig_text(),
      "      plant: { time_constant_ms: 30, latency_ms: 5, noise_deg: 0.2, deadband_deg: 0.15, "
      "backlash_deg: 0.5 }\n      expect_direction: { eye_yaw_l_deg",
      "      plant: { time_constant_ms: 30, latency_ms: 5, noise_deg: 0.2, deadband_deg: 0.15, "
      "backlash_deg: 0.5, thermal_time_constant_s: 6 }\n      expect_direction: { eye_yaw_l_deg");
}

TEST_F(ControllerProtection, AStalledServoHeatsUpDeratesAndFinallyFaults) {
  start(fast_thermal_rig());
  const std::size_t pan = actuator("eyes_pan");
  // Blocked at 5 deg, commanded to 25: the error stays near full effort
  // (8 deg) even at the derate floor (12.5 deg), so it keeps heating.
  bus().block_above(pan, 5.0 * kDeg);
  look(25.0);
  double derated_at = -1.0, t = 0.0;
  while (t < 10.0 && head_->controller().state() == SafetyState::kRunning) {
    run(0.01, true);
    t += 0.01;
    if (derated_at < 0 && head_->controller().protection(pan).factor < 1.0) derated_at = t;
  }
  ASSERT_EQ(head_->controller().state(), SafetyState::kFault) << "after " << t << " s";
  EXPECT_GT(derated_at, 0.0) << "derated before it faulted";
  EXPECT_LT(derated_at, t);
  EXPECT_NE(last_event_detail().find("eyes_pan temperature"), std::string::npos);
  // The controller faulted before the servo's own protection (72 C) tripped.
  EXPECT_FALSE(bus().status().fault) << bus().status().reason;
  EXPECT_LT(bus().plant(pan).temperature_c(), 72.0);
}

TEST_F(ControllerProtection, DeratingKeepsAPushingServoBelowTheFaultLine) {
  start(fast_thermal_rig());
  const std::size_t pan = actuator("eyes_pan");
  // Blocked at 5 deg, commanded to 12: pulling the command toward rest
  // lowers the push, and the heat settles between the lines.
  bus().block_above(pan, 5.0 * kDeg);
  look(12.0);
  double peak = 0.0, lowest_factor = 1.0;
  for (int k = 0; k < 3000; ++k) {
    run(0.01);
    peak = std::max(peak, bus().plant(pan).temperature_c());
    lowest_factor = std::min(lowest_factor, head_->controller().protection(pan).factor);
  }
  EXPECT_EQ(head_->controller().state(), SafetyState::kRunning);
  EXPECT_GT(peak, 60.0) << "it did get hot";
  EXPECT_LT(peak, 70.0);
  EXPECT_LT(lowest_factor, 1.0);
  EXPECT_LT(command_deg(pan), 12.0);
}

TEST(ProtectionConfig, ALimitTheBusCannotReportIsRefusedNamingTheBusType) {
  // The default rig's actuators are on CAN and Modbus buses.
  std::string t = testing::read_text(testing::source_path("config/rigs/default.yaml"));
  const std::string map = "      map:\n        terms: { neck_pan_deg: 1.0 }";
  t = testing::replaced_once(
      t, map, "      protection: { temperature_c: { derate: 60, fault: 70 } }\n" + map);
  try {
    load_rig(t);
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("protection.temperature_c"), std::string::npos) << what;
    EXPECT_NE(what.find("does not report temperature"), std::string::npos) << what;
    EXPECT_NE(what.find("type can"), std::string::npos) << what;
    EXPECT_NE(what.find(".yaml:"), std::string::npos) << what;
  }
}

TEST(ProtectionConfig, DerateMustBeBelowFaultAndUnitsChecked) {
  const std::string from = "temperature_c: { derate: 60, fault: 70 }";
  for (const auto& [to, expected] :
       {std::pair<std::string, std::string>{"temperature_c: { derate: 70, fault: 60 }",
                                            "derate below fault"},
        {"temperature_c: { derate: 60, fault: 70, warn: 65 }", "warn"},
        {"temperature_c: { derate: 60, fault: 70 }\n        load: { fault: 1.5 }", "load.fault"},
        {"temperature_c: { derate: 60, fault: 70 }\n        extreme: { band_mm: 2, budget_s: 5, "
         "cooldown_s: 5 }",
         "band_mm"}}) {
    try {
      load_rig(testing::replaced_once(rig_text(), from, to));
      ADD_FAILURE() << "accepted: " << to;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace facectl
