#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "drivers/hid/gamepad_report.hpp"
#include "drivers/hid/hid_descriptor.hpp"

namespace facectl {

// The axis slots of a layout made from a report descriptor, always in this
// order, so that config can name them before the device is seen. A slot the
// device lacks is not `present` and reads 0.
inline constexpr std::array<const char*, 13> kDescriptorAxisNames = {
    "x",    "y",     "z",     "rx",    "ry",          "rz",   "slider",
    "dial", "wheel", "hat_x", "hat_y", "accelerator", "brake"};
// Buttons are button_1 .. button_32, by their Button page usage.
inline constexpr int kDescriptorButtons = 32;
std::string descriptor_button_name(int usage);

// The gamepad layout a descriptor declares: the input fields of its first
// Joystick, Game Pad or Multi-axis Controller application collection (one
// report id: the first such field's), by usage. Variable fields only; a second
// field with the same usage is ignored. Throws std::invalid_argument when the
// descriptor is malformed or declares no such collection.
GamepadLayout gamepad_layout_from_descriptor(std::span<const std::uint8_t> descriptor);
GamepadLayout gamepad_layout_from_fields(const std::vector<HidInputField>& fields);

// One line per present axis and button, for `facectl gamepad layout`.
std::string describe(const GamepadLayout& layout);

}  // namespace facectl
