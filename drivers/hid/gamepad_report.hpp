#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace facectl {

// Where a gamepad's axes and buttons sit in its HID input report. Gamepads
// differ, so this comes from config (or from the report descriptor, read by
// hand once: docs/PROTOCOLS.md, "HID gamepad").
struct GamepadLayout {
  struct Axis {
    std::string name;
    int byte = 0;  // offset in the report, after the report id if any
    int bits = 8;  // 8 or 16 (little-endian)
    bool is_signed = false;
    double min = 0.0;    // raw value that maps to -1
    double max = 255.0;  // raw value that maps to +1
  };
  struct Button {
    std::string name;
    int byte = 0;
    int bit = 0;
  };
  int report_id = -1;  // -1: the device uses no report ids
  std::vector<Axis> axes;
  std::vector<Button> buttons;
};

inline constexpr std::size_t kMaxGamepadAxes = 16;

// One decoded report: axes in -1..1, buttons as bits in layout order.
struct GamepadState {
  std::array<double, kMaxGamepadAxes> axes{};
  std::uint32_t buttons = 0;
  bool connected = false;
  std::uint64_t reports = 0;     // reports decoded since start
  std::int64_t received_ns = 0;  // CLOCK_MONOTONIC of the newest report
};

// Decodes `report` into `state` (axes and buttons only). False, with `state`
// untouched, when the report is too short for the layout or carries another
// report id.
bool decode_gamepad_report(const GamepadLayout& layout, std::span<const std::uint8_t> report,
                           GamepadState& state);

// Checks a layout: at most 16 axes and 32 buttons, sane offsets and widths.
// Throws std::invalid_argument naming the axis or button.
void validate(const GamepadLayout& layout);

}  // namespace facectl
