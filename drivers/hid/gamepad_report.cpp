#include "drivers/hid/gamepad_report.hpp"

#include <algorithm>
#include <stdexcept>

namespace facectl {

bool decode_gamepad_report(const GamepadLayout& layout, std::span<const std::uint8_t> report,
                           GamepadState& state) {
  std::size_t base = 0;
  if (layout.report_id >= 0) {
    if (report.empty() || report[0] != layout.report_id) return false;
    base = 1;
  }
  for (const auto& a : layout.axes) {
    if (base + static_cast<std::size_t>(a.byte + a.bits / 8) > report.size()) return false;
  }
  for (const auto& b : layout.buttons) {
    if (base + static_cast<std::size_t>(b.byte) >= report.size()) return false;
  }
  for (std::size_t i = 0; i < layout.axes.size(); ++i) {
    const auto& a = layout.axes[i];
    const std::uint8_t* p = &report[base + static_cast<std::size_t>(a.byte)];
    double raw = 0.0;
    if (a.bits == 8) {
      raw = a.is_signed ? static_cast<double>(static_cast<std::int8_t>(p[0])) : p[0];
    } else {
      const auto u = static_cast<std::uint16_t>(p[0] | (p[1] << 8));
      raw = a.is_signed ? static_cast<double>(static_cast<std::int16_t>(u)) : u;
    }
    const double v = -1.0 + 2.0 * (raw - a.min) / (a.max - a.min);
    state.axes[i] = std::clamp(v, -1.0, 1.0);
  }
  std::uint32_t buttons = 0;
  for (std::size_t i = 0; i < layout.buttons.size(); ++i) {
    const auto& b = layout.buttons[i];
    if ((report[base + static_cast<std::size_t>(b.byte)] >> b.bit) & 1) buttons |= 1u << i;
  }
  state.buttons = buttons;
  return true;
}

void validate(const GamepadLayout& layout) {
  if (layout.axes.size() > kMaxGamepadAxes || layout.buttons.size() > 32) {
    throw std::invalid_argument("gamepad layout: at most 16 axes and 32 buttons");
  }
  for (const auto& a : layout.axes) {
    if (a.byte < 0 || a.byte > 63 || (a.bits != 8 && a.bits != 16) || !(a.max != a.min)) {
      throw std::invalid_argument("gamepad axis '" + a.name +
                                  "': expected byte 0..63, bits 8 or 16, min != max");
    }
  }
  for (const auto& b : layout.buttons) {
    if (b.byte < 0 || b.byte > 63 || b.bit < 0 || b.bit > 7) {
      throw std::invalid_argument("gamepad button '" + b.name + "': expected byte 0..63, bit 0..7");
    }
  }
}

}  // namespace facectl
