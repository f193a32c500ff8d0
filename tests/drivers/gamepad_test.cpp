// Gamepad reports decoded byte for byte, and the puppeteering mapping.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "drivers/hid/gamepad_mapping.hpp"
#include "drivers/hid/gamepad_report.hpp"

namespace facectl {
namespace {

// The QEMU test's virtual gamepad: [x int8][y int8][8 buttons].
GamepadLayout two_axes_eight_buttons() {
  GamepadLayout l;
  l.axes = {{"x", 0, 8, true, -127, 127}, {"y", 1, 8, true, -127, 127}};
  for (int b = 0; b < 8; ++b) l.buttons.push_back({"b" + std::to_string(b), 2, b});
  return l;
}

TEST(GamepadReport, SignedAxesAndButtonBitsDecode) {
  GamepadState s;
  const std::vector<std::uint8_t> report{0x7F, 0x81, 0x05};  // x +127, y -127, buttons 0 and 2
  ASSERT_TRUE(decode_gamepad_report(two_axes_eight_buttons(), report, s));
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[1], -1.0);
  EXPECT_EQ(s.buttons, 0x05u);
  const std::vector<std::uint8_t> centre{0x00, 0x00, 0x00};
  ASSERT_TRUE(decode_gamepad_report(two_axes_eight_buttons(), centre, s));
  EXPECT_DOUBLE_EQ(s.axes[0], 0.0);
}

TEST(GamepadReport, SixteenBitAxesReportIdsAndShortReports) {
  GamepadLayout l;
  l.report_id = 1;
  l.axes = {{"lx", 0, 16, false, 0, 65535}};
  GamepadState s;
  const std::vector<std::uint8_t> report{0x01, 0xFF, 0xFF};
  ASSERT_TRUE(decode_gamepad_report(l, report, s));
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  const std::vector<std::uint8_t> other{0x02, 0x00, 0x00};
  EXPECT_FALSE(decode_gamepad_report(l, other, s)) << "another report id";
  const std::vector<std::uint8_t> short_report{0x01, 0x00};
  EXPECT_FALSE(decode_gamepad_report(l, short_report, s));
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0) << "a refused report leaves the state alone";
}

TEST(GamepadReport, BadLayoutsAreRefusedByName) {
  GamepadLayout l;
  l.axes = {{"jaw", 0, 33, false, 0, 255}};
  try {
    validate(l);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gamepad axis 'jaw'"), std::string::npos) << e.what();
  }
}

TEST(GamepadMapping, AxesWithDeadZoneAndButtonsDriveSignals) {
  // Signal 0: jaw pitch from the y axis, 0..0.3 rad; signal 1: a smile on button 2.
  GamepadMapping m({{GamepadTerm::Source::kAxis, 1, 0, 0.15, 0.15, 0.1},
                    {GamepadTerm::Source::kButton, 2, 1, 0.8, 0.0, 0.0}});
  GamepadState s;
  std::array<double, 3> pose{9.0, 9.0, 9.0};
  s.axes[1] = 0.05;  // inside the dead zone
  m.apply(s, pose);
  EXPECT_DOUBLE_EQ(pose[0], 0.15);
  EXPECT_DOUBLE_EQ(pose[1], 0.0);
  EXPECT_DOUBLE_EQ(pose[2], 9.0) << "unmapped signals are left alone";
  s.axes[1] = 1.0;
  s.buttons = 1u << 2;
  m.apply(s, pose);
  EXPECT_DOUBLE_EQ(pose[0], 0.3);
  EXPECT_DOUBLE_EQ(pose[1], 0.8);
  s.axes[1] = 0.55;  // halfway between the dead zone and full scale
  m.apply(s, pose);
  EXPECT_DOUBLE_EQ(pose[0], 0.15 + 0.15 * 0.5);
}

}  // namespace
}  // namespace facectl
