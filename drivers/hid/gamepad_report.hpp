#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace facectl {

// Where a gamepad's axes and buttons sit in its HID input report: from the
// device's report descriptor (gamepad_layout_from_descriptor), or written in
// config as an override (docs/PROTOCOLS.md, "HID gamepad").
struct GamepadLayout {
  // A hat switch gives two axes, each -1, 0 or +1 (up is hat_y = -1).
  enum class Kind { kLinear, kHatX, kHatY };
  struct Axis {
    std::string name;
    int byte = 0;  // offset in the report, after the report id if any
    int bits = 8;  // 1..32, little-endian
    bool is_signed = false;
    double min = 0.0;    // raw value that maps to -1
    double max = 255.0;  // raw value that maps to +1
    int bit = 0;         // first bit within `byte`, 0..7 (HID packs fields LSB first)
    Kind kind = Kind::kLinear;
    bool present = true;  // false: a slot the device lacks; reads 0
  };
  struct Button {
    std::string name;
    int byte = 0;
    int bit = 0;
    bool present = true;
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

// Checks a layout: at most 16 axes and 32 buttons, fields within 64 bytes,
// 1..32 bits wide.
// Throws std::invalid_argument naming the axis or button.
void validate(const GamepadLayout& layout);

}  // namespace facectl
