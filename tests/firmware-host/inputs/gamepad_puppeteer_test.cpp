// Puppeteering and record mode: gamepad reports (injected as raw HID reports,
// decoded with the shipped config's layout) become face commands in the
// controller's mailbox through the configured mapping, and what was
// performed is written as a show file that Show::load reads back to the same
// poses.
#include "firmware-host/inputs/gamepad_puppeteer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>

#include "firmware-host/config/loaded_config.hpp"
#include "tests/drivers/facectl_process.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

class Puppeteering : public ::testing::Test {
 protected:
  Puppeteering() : cfg_(load_config(default_config_path())), pad_(*cfg_.runtime.gamepad) {}

  // A report of the shipped layout: x, y (int8), buttons.
  void report(int x, int y, std::uint8_t buttons, bool connected = true) {
    const std::uint8_t raw[3] = {static_cast<std::uint8_t>(static_cast<std::int8_t>(x)),
                                 static_cast<std::uint8_t>(static_cast<std::int8_t>(y)), buttons};
    GamepadState s = state_;
    s.connected = connected;
    ASSERT_TRUE(decode_gamepad_report(pad_.layout, raw, s));
    state_ = s;
    queue_.push_back(s);
  }
  GamepadPuppeteer::Source source() {
    return [this](GamepadState& out) {
      if (queue_.empty()) return false;
      out = queue_.front();
      queue_.pop_front();
      return true;
    };
  }

  LoadedConfig cfg_;
  const GamepadConfig& pad_;
  GamepadState state_;
  std::deque<GamepadState> queue_;
  LatestValueMailbox<FaceCommand> mailbox_;
};

TEST_F(Puppeteering, ReportsAreMappedOntoTheNeutralPoseAndPublished) {
  const ControllerModel& m = cfg_.built.model;
  GamepadPuppeteer p(source(), GamepadMapping(pad_.terms), m.neutral, mailbox_, pad_.rate_hz);
  FaceCommand cmd;
  p.step(1'000'000);
  EXPECT_FALSE(mailbox_.consume(cmd)) << "nothing before the gamepad connects";

  report(127, -127, 0x01);  // x right, y full down, button a
  p.step(2'000'000);
  ASSERT_TRUE(mailbox_.consume(cmd));
  // jaw_pitch_deg = 9 + 9·y = 0; jaw_yaw_deg = 3·x = 3; a: zygomaticus majors 0.8.
  EXPECT_NEAR(cmd.values[m.layout.jaw_pitch()], 0.0, 1e-12);
  EXPECT_NEAR(cmd.values[m.layout.jaw_yaw()], 3.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(cmd.values[*m.layout.find("zygomaticus_major_l")], 0.8);
  EXPECT_DOUBLE_EQ(cmd.values[*m.layout.find("eyelid_closure_l")], 0.0);
  EXPECT_EQ(cmd.values[*m.layout.find("procerus_l")], m.neutral[*m.layout.find("procerus_l")]);

  report(0, 127, 0x02);  // y full up, button b
  p.step(3'000'000);
  ASSERT_TRUE(mailbox_.consume(cmd));
  EXPECT_NEAR(cmd.values[m.layout.jaw_pitch()], 18.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(cmd.values[*m.layout.find("eyelid_closure_r")], 1.0);

  report(0, 0, 0, false);  // unplugged: silence, so the input watchdog eases to neutral
  p.step(4'000'000);
  EXPECT_FALSE(mailbox_.consume(cmd));
  EXPECT_FALSE(p.connected());
  EXPECT_EQ(p.published(), 2u);
}

TEST_F(Puppeteering, ARecordedPerformanceLoadsBackAsTheSameShow) {
  const ControllerModel& m = cfg_.built.model;
  ShowRecorder recorder(m.layout, m.neutral);
  GamepadPuppeteer p(source(), GamepadMapping(pad_.terms), m.neutral, mailbox_, pad_.rate_hz,
                     &recorder);
  // 3 s at 250 Hz: the jaw sweeps with y for 1.5 s, then a 1 s hold with
  // button a, then the eyes close with b.
  std::vector<std::pair<double, FaceCommand>> performed;
  for (int k = 0; k < 750; ++k) {
    const double t = k / 250.0;
    if (t < 1.5) {
      report(static_cast<int>(std::lround(60 * std::sin(4 * t))),
             static_cast<int>(std::lround(127 * std::sin(3 * t))), 0);
    } else if (t < 2.5) {
      if (k % 25 == 0) report(0, 64, 0x01);
    } else if (k % 50 == 0) {
      report(0, 0, 0x02);
    }
    p.step(5'000'000'000 + static_cast<std::int64_t>(std::llround(t * 1e9)));
    FaceCommand cmd;
    if (mailbox_.consume(cmd)) performed.emplace_back(t, cmd);
  }
  ASSERT_EQ(performed.size(), 750u);
  EXPECT_LT(recorder.keyframes(), 500u);  // the int8 sweep steps keep most of theirs

  testing::TempFile file("", ".yaml");
  recorder.write(file.path(), "take1");
  const Show show = Show::load(file.path(), m.layout, m.neutral, cfg_.expressions);
  EXPECT_EQ(show.name(), "take1");
  EXPECT_NEAR(show.duration(), 2.996, 1e-9);
  // Every performed pose comes back within the recorder's tolerance (plus the
  // 9 digits written), button steps included.
  std::array<double, kMaxFaceSignals> pose{};
  for (const auto& [t, cmd] : performed) {
    show.evaluate(t, pose);
    for (std::size_t i = 0; i < m.layout.size(); ++i) {
      ASSERT_NEAR(pose[i], cmd.values[i], 1.01e-3)
          << "t " << t << " signal " << m.layout.signal(i).name;
      if (m.layout.signal(i).kind == SignalKind::kAngle) {
        ASSERT_NEAR(pose[i], cmd.values[i], 1.01e-4);
      }
    }
  }
  // The 1 s hold costs at most 3 keyframes.
  int in_hold = 0;
  for (const auto& k : show.keyframes()) in_hold += k.t > 1.5 && k.t < 2.5;
  EXPECT_LE(in_hold, 3);
}

TEST(PuppeteeringProcess, RecordShowNeedsTheGamepadAndAnEmptyTakeIsNotWritten) {
  std::string out;
  EXPECT_EQ(testing::run_facectl("run --quiet --record-show /tmp/x.yaml", out), 2) << out;
  EXPECT_NE(out.find("--record-show: expected --gamepad"), std::string::npos) << out;
  // No such gamepad on this machine: the run idles at neutral and writes nothing.
  testing::TempFile take("", ".yaml");
  std::remove(take.path().c_str());
  EXPECT_EQ(testing::run_facectl(
                "run --quiet --gamepad --duration 0.5 --record-show " + take.path(), out),
            1)
      << out;
  EXPECT_NE(out.find("puppeteering from gamepad"), std::string::npos) << out;
  EXPECT_NE(out.find("the gamepad sent nothing; no show written"), std::string::npos) << out;
}

}  // namespace
}  // namespace facectl
