// HID report descriptors parsed to input fields, and gamepad layouts made from
// them: real pads' descriptors (tests/drivers/hid_descriptors/SOURCES.md)
// decoding reports to known axes and buttons, packed bit fields, and
// malformed descriptors refused by byte offset.
#include "drivers/hid/hid_descriptor.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drivers/hid/gamepad_descriptor_layout.hpp"

namespace facectl {
namespace {

std::vector<std::uint8_t> real_descriptor(const std::string& name) {
  const std::string path =
      std::string(FACECTL_SOURCE_DIR) + "/tests/drivers/hid_descriptors/" + name + ".hex";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<std::uint8_t> out;
  std::string byte;
  while (in >> byte) out.push_back(static_cast<std::uint8_t>(std::stoul(byte, nullptr, 16)));
  return out;
}

// Index of a named slot (kDescriptorAxisNames).
std::size_t axis(const std::string& name) {
  for (std::size_t i = 0; i < kDescriptorAxisNames.size(); ++i) {
    if (name == kDescriptorAxisNames[i]) return i;
  }
  throw std::invalid_argument(name);
}

std::uint32_t buttons(std::initializer_list<int> pressed) {
  std::uint32_t m = 0;
  for (int b : pressed) m |= 1u << (b - 1);
  return m;
}

std::string error_of(const std::vector<std::uint8_t>& d) {
  try {
    parse_hid_descriptor(d);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(HidDescriptor, SaitekJoystickHasItsHatInTheHighNibble) {
  const GamepadLayout l = gamepad_layout_from_descriptor(real_descriptor("saitek_joystick"));
  EXPECT_EQ(l.report_id, 1);
  const auto& hat = l.axes[axis("hat_x")];
  ASSERT_TRUE(hat.present);
  EXPECT_EQ(hat.byte, 5);
  EXPECT_EQ(hat.bit, 4);
  EXPECT_EQ(hat.bits, 4);
  EXPECT_FALSE(l.axes[axis("z")].present) << "its rudder and throttle are not Generic Desktop axes";
  EXPECT_TRUE(l.buttons[11].present);
  EXPECT_FALSE(l.buttons[12].present) << "12 buttons";

  // x 255, y 0, rudder and throttle centred, buttons 1 and 3, then buttons 10
  // and 12 in the low nibble and the hat pointing east (2) in the high one.
  const std::vector<std::uint8_t> report{0x01, 0xFF, 0x00, 0x80, 0x80, 0x05, 0x2A};
  GamepadState s;
  ASSERT_TRUE(decode_gamepad_report(l, report, s));
  EXPECT_DOUBLE_EQ(s.axes[axis("x")], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("y")], -1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_x")], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_y")], 0.0);
  EXPECT_EQ(s.buttons, buttons({1, 3, 10, 12}));
  // The hat's null state (15, beyond logical 0..7) is centred.
  const std::vector<std::uint8_t> released{0x01, 0x80, 0x80, 0x80, 0x80, 0x00, 0xF0};
  ASSERT_TRUE(decode_gamepad_report(l, released, s));
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_x")], 0.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_y")], 0.0);
  EXPECT_EQ(s.buttons, 0u);
  EXPECT_FALSE(decode_gamepad_report(l, {{0x02, 0, 0, 0, 0, 0, 0}}, s)) << "report id 2";
}

TEST(HidDescriptor, AsusGamepadNamesButtonsByUsageAndReadsBrakeAndAccelerator) {
  const GamepadLayout l = gamepad_layout_from_descriptor(real_descriptor("asus_gamepad"));
  EXPECT_EQ(l.report_id, 1);
  // Its buttons are usages 1 2 4 5 7 8 14 15 13, in that order in the report.
  EXPECT_TRUE(l.buttons[0].present);
  EXPECT_FALSE(l.buttons[2].present) << "no button 3";
  EXPECT_EQ(l.buttons[12].byte, 1);  // button 13 is the report's ninth bit
  EXPECT_EQ(l.buttons[12].bit, 0);
  // Bits 0 and 3 (buttons 1 and 5), bit 8 (button 13), hat 6 (west);
  // X 0, Y 255, Z 128, Rz 127, Brake 255, Accelerator 0.
  const std::vector<std::uint8_t> report{0x01, 0x09, 0x61, 0x00, 0xFF, 0x80, 0x7F, 0xFF, 0x00};
  GamepadState s;
  ASSERT_TRUE(decode_gamepad_report(l, report, s));
  EXPECT_EQ(s.buttons, buttons({1, 5, 13}));
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_x")], -1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_y")], 0.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("x")], -1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("y")], 1.0);
  EXPECT_NEAR(s.axes[axis("z")], 1.0 / 255.0, 1e-12);
  EXPECT_NEAR(s.axes[axis("rz")], -1.0 / 255.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.axes[axis("brake")], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("accelerator")], -1.0);
}

TEST(HidDescriptor, DualShock4PacksHatAndFourteenButtonsAcrossBytes) {
  const GamepadLayout l = gamepad_layout_from_descriptor(real_descriptor("sony_ds4_usb"));
  EXPECT_EQ(l.report_id, 1);
  EXPECT_EQ(l.axes[axis("hat_x")].byte, 4);
  EXPECT_EQ(l.axes[axis("hat_x")].bit, 0);
  EXPECT_EQ(l.buttons[0].byte, 4);
  EXPECT_EQ(l.buttons[0].bit, 4);
  EXPECT_EQ(l.buttons[13].byte, 6);
  EXPECT_EQ(l.buttons[13].bit, 1);
  EXPECT_FALSE(l.buttons[14].present);
  EXPECT_EQ(l.axes[axis("rx")].byte, 7);  // the L2 and R2 triggers
  // Sticks centred, hat null (8) with cross (button 2), share and options
  // (9, 10), PS and touchpad (13, 14) next to a full 6-bit frame counter,
  // L2 pressed, R2 released.
  std::vector<std::uint8_t> report(64, 0);
  const std::uint8_t head[] = {0x01, 0x80, 0x80, 0x80, 0x80, 0x28, 0x30, 0xFF, 0xFF, 0x00};
  std::copy(std::begin(head), std::end(head), report.begin());
  GamepadState s;
  ASSERT_TRUE(decode_gamepad_report(l, report, s));
  EXPECT_EQ(s.buttons, buttons({2, 9, 10, 13, 14}));
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_x")], 0.0);
  EXPECT_NEAR(s.axes[axis("x")], 1.0 / 255.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.axes[axis("rx")], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("ry")], -1.0);
  report[5] = 0x01;  // north-east, nothing pressed
  report[6] = report[7] = 0x00;
  ASSERT_TRUE(decode_gamepad_report(l, report, s));
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_x")], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_y")], -1.0);
  EXPECT_EQ(s.buttons, 0u);
}

TEST(HidDescriptor, Ps3ControllerSkipsItsPaddingByteAndConstantBits) {
  const GamepadLayout l = gamepad_layout_from_descriptor(real_descriptor("sony_ps3"));
  EXPECT_EQ(l.report_id, 1);
  EXPECT_TRUE(l.buttons[18].present);
  EXPECT_FALSE(l.buttons[19].present) << "19 buttons";
  EXPECT_EQ(l.axes[axis("x")].byte, 5);
  const std::vector<std::uint8_t> report{0x01, 0x00, 0x01, 0x80, 0xFC,
                                         0xFF, 0x00, 0xFF, 0x80, 0x7F};
  GamepadState s;
  ASSERT_TRUE(decode_gamepad_report(l, report, s));
  EXPECT_EQ(s.buttons, buttons({1, 16, 19})) << "the constant bits after button 19 are ignored";
  EXPECT_DOUBLE_EQ(s.axes[axis("x")], -1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("y")], 1.0);
}

TEST(HidDescriptor, TwelveBitAndSignedTenBitAxesDecodeAcrossByteBoundaries) {
  // Game Pad: X, Y 12 bits 0..4095; Rx signed 10 bits -512..511; 2 bits pad;
  // a 4-bit hat 1..8 (a 1-based hat, as some pads have); 4 buttons.
  const std::vector<std::uint8_t> d{
      0x05, 0x01, 0x09, 0x05, 0xA1, 0x01, 0x09, 0x30, 0x09, 0x31, 0x15, 0x00, 0x26, 0xFF,
      0x0F, 0x75, 0x0C, 0x95, 0x02, 0x81, 0x02, 0x09, 0x33, 0x16, 0x00, 0xFE, 0x26, 0xFF,
      0x01, 0x75, 0x0A, 0x95, 0x01, 0x81, 0x02, 0x75, 0x02, 0x81, 0x03, 0x09, 0x39, 0x15,
      0x01, 0x25, 0x08, 0x75, 0x04, 0x81, 0x42, 0x05, 0x09, 0x19, 0x01, 0x29, 0x04, 0x15,
      0x00, 0x25, 0x01, 0x75, 0x01, 0x95, 0x04, 0x81, 0x02, 0xC0};
  const auto fields = parse_hid_descriptor(d);
  ASSERT_EQ(fields.size(), 8u);
  EXPECT_EQ(fields[1].bit_offset, 12);
  EXPECT_EQ(fields[2].bit_offset, 24);
  EXPECT_EQ(fields[2].logical_min, -512);
  EXPECT_EQ(fields[2].logical_max, 511);
  EXPECT_EQ(fields[3].bit_offset, 36) << "after 2 bits of padding";
  const GamepadLayout l = gamepad_layout_from_fields(fields);
  EXPECT_EQ(l.report_id, -1);
  // X 4095, Y 0, Rx -512 (0x200), hat 3 (east, 1-based), buttons 1 and 4.
  const std::uint32_t bits = 0xFFFu | (0x000u << 12) | (0x200u << 24);
  const std::vector<std::uint8_t> report{
      static_cast<std::uint8_t>(bits),          static_cast<std::uint8_t>(bits >> 8),
      static_cast<std::uint8_t>(bits >> 16),    static_cast<std::uint8_t>(bits >> 24),
      static_cast<std::uint8_t>(0x02 | 3 << 4), 0x09};
  GamepadState s;
  ASSERT_TRUE(decode_gamepad_report(l, report, s));
  EXPECT_DOUBLE_EQ(s.axes[axis("x")], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("y")], -1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("rx")], -1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_x")], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[axis("hat_y")], 0.0);
  EXPECT_EQ(s.buttons, buttons({1, 4}));
  EXPECT_FALSE(decode_gamepad_report(l, std::span(report).first(5), s)) << "one byte short";
}

TEST(HidDescriptor, LogicalRangesAreSignExtendedPushAndPopRestoreGlobals) {
  // Logical Minimum 0x81 is -127 (1 byte), 0x8001 is -32767 (2 bytes); a
  // 1-byte Logical Maximum 0xFF after a non-negative minimum is 255 (as
  // the Linux HID core reads it).
  const std::vector<std::uint8_t> d{
      0x05, 0x01, 0x09, 0x04, 0xA1, 0x01, 0x09, 0x30, 0x15, 0x81, 0x25, 0x7F, 0x75, 0x08,
      0x95, 0x01, 0xA4, 0x81, 0x02, 0x09, 0x31, 0x16, 0x01, 0x80, 0x26, 0xFF, 0x7F, 0x75,
      0x10, 0x81, 0x02, 0xB4, 0x09, 0x32, 0x15, 0x00, 0x25, 0xFF, 0x81, 0x02, 0xC0};
  const auto f = parse_hid_descriptor(d);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].logical_min, -127);
  EXPECT_EQ(f[1].logical_min, -32767);
  EXPECT_EQ(f[1].logical_max, 32767);
  EXPECT_EQ(f[1].bit_size, 16);
  EXPECT_EQ(f[2].bit_size, 8) << "Pop restored Report Size 8";
  EXPECT_EQ(f[2].bit_offset, 24);
  EXPECT_EQ(f[2].logical_max, 255);
  EXPECT_EQ(f[2].application, 0x00010004u);
}

TEST(HidDescriptor, MalformedDescriptorsNameTheByteAndItem) {
  EXPECT_EQ(error_of({0x05, 0x01, 0x26, 0xFF}),
            "HID report descriptor: byte 2, item 0x26: expected 2 data bytes, 1 left");
  EXPECT_EQ(error_of({0x05, 0x01, 0xC0}),
            "HID report descriptor: byte 2, item 0xC0: expected a Collection before this End "
            "Collection");
  EXPECT_EQ(error_of({0xB4}),
            "HID report descriptor: byte 0, item 0xB4: expected a Push before "
            "this Pop");
  EXPECT_EQ(error_of({0x05, 0x01, 0xA1, 0x01}),
            "HID report descriptor: byte 4: expected an End Collection for each Collection "
            "before the end");
  EXPECT_EQ(error_of({0x85, 0x00}),
            "HID report descriptor: byte 0, item 0x85: expected Report ID 1..255, got 0");
  EXPECT_EQ(error_of({0x75, 0x08, 0x96, 0x00, 0x20}),
            "HID report descriptor: byte 2, item 0x96: expected Report Count 0..4096, got 8192");
  EXPECT_EQ(error_of({0x19, 0x05, 0x29, 0x01, 0x75, 0x01, 0x95, 0x01, 0x81, 0x02}),
            "HID report descriptor: byte 8, item 0x81: expected Usage Minimum and Usage Maximum, "
            "minimum <= maximum");
  EXPECT_EQ(error_of({0x0C}),  // type 3
            "HID report descriptor: byte 0, item 0x0C: expected a main, global or local item "
            "(type 3 is reserved)");
  // A mouse is no gamepad.
  const std::vector<std::uint8_t> mouse{0x05, 0x01, 0x09, 0x02, 0xA1, 0x01, 0x09, 0x30,
                                        0x75, 0x08, 0x95, 0x01, 0x81, 0x06, 0xC0};
  EXPECT_THROW(gamepad_layout_from_descriptor(mouse), std::invalid_argument);
}

TEST(HidDescriptor, DescribeListsWhatWasFound) {
  const std::string text =
      describe(gamepad_layout_from_descriptor(real_descriptor("sony_ds4_usb")));
  EXPECT_NE(text.find("report id 1"), std::string::npos) << text;
  EXPECT_NE(text.find("hat_x        byte  4 bit 0,  4 bits unsigned, 0..7 hat"), std::string::npos)
      << text;
  EXPECT_NE(text.find("button button_14    byte  6 bit 1"), std::string::npos) << text;
}

}  // namespace
}  // namespace facectl
