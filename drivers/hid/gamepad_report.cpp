#include "drivers/hid/gamepad_report.hpp"

#include <algorithm>
#include <stdexcept>

namespace facectl {

namespace {

constexpr int kMaxReportBytes = 64;

// One past the last byte an axis reads.
std::size_t end_byte(const GamepadLayout::Axis& a) {
  return static_cast<std::size_t>((a.byte * 8 + a.bit + a.bits + 7) / 8);
}

std::int64_t read_bits(const std::uint8_t* p, int bit, int bits, bool is_signed) {
  std::uint64_t v = 0;
  const int bytes = (bit + bits + 7) / 8;  // at most 5
  for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  v = (v >> bit) & ((std::uint64_t{1} << bits) - 1);
  if (is_signed && ((v >> (bits - 1)) & 1)) v |= ~((std::uint64_t{1} << bits) - 1);
  return static_cast<std::int64_t>(v);
}

// Hat switch directions, clockwise from north, as the Linux HID core maps
// them (drivers/hid/hid-input.c, hid_hat_to_axis); out of range is centred
// (the null state).
constexpr int kHatX[8] = {0, 1, 1, 1, 0, -1, -1, -1};
constexpr int kHatY[8] = {-1, -1, 0, 1, 1, 1, 0, -1};

double hat(const GamepadLayout::Axis& a, std::int64_t raw) {
  const auto lo = static_cast<std::int64_t>(a.min), hi = static_cast<std::int64_t>(a.max);
  if (raw < lo || raw > hi) return 0.0;
  const auto dir = static_cast<std::size_t>((raw - lo) * 8 / (hi - lo + 1));
  return a.kind == GamepadLayout::Kind::kHatX ? kHatX[dir] : kHatY[dir];
}

}  // namespace

bool decode_gamepad_report(const GamepadLayout& layout, std::span<const std::uint8_t> report,
                           GamepadState& state) {
  std::size_t base = 0;
  if (layout.report_id >= 0) {
    if (report.empty() || report[0] != layout.report_id) return false;
    base = 1;
  }
  for (const auto& a : layout.axes) {
    if (a.present && base + end_byte(a) > report.size()) return false;
  }
  for (const auto& b : layout.buttons) {
    if (b.present && base + static_cast<std::size_t>(b.byte) >= report.size()) return false;
  }
  for (std::size_t i = 0; i < layout.axes.size(); ++i) {
    const auto& a = layout.axes[i];
    if (!a.present) {
      state.axes[i] = 0.0;
      continue;
    }
    const std::int64_t raw =
        read_bits(&report[base + static_cast<std::size_t>(a.byte)], a.bit, a.bits, a.is_signed);
    if (a.kind != GamepadLayout::Kind::kLinear) {
      state.axes[i] = hat(a, raw);
      continue;
    }
    const double v = -1.0 + 2.0 * (static_cast<double>(raw) - a.min) / (a.max - a.min);
    state.axes[i] = std::clamp(v, -1.0, 1.0);
  }
  std::uint32_t buttons = 0;
  for (std::size_t i = 0; i < layout.buttons.size(); ++i) {
    const auto& b = layout.buttons[i];
    if (b.present && (report[base + static_cast<std::size_t>(b.byte)] >> b.bit) & 1) {
      buttons |= 1u << i;
    }
  }
  state.buttons = buttons;
  return true;
}

void validate(const GamepadLayout& layout) {
  if (layout.axes.size() > kMaxGamepadAxes || layout.buttons.size() > 32) {
    throw std::invalid_argument("gamepad layout: at most 16 axes and 32 buttons");
  }
  for (const auto& a : layout.axes) {
    if (!a.present) continue;
    const bool hat = a.kind != GamepadLayout::Kind::kLinear;
    if (a.byte < 0 || a.bit < 0 || a.bit > 7 || a.bits < 1 || a.bits > 32 ||
        end_byte(a) > kMaxReportBytes || !(a.max != a.min) ||
        (hat && !(a.min < a.max && a.min >= -2147483648.0 && a.max <= 2147483647.0))) {
      throw std::invalid_argument("gamepad axis '" + a.name +
                                  "': expected byte 0..63, bit 0..7, bits 1..32 within 64 "
                                  "bytes, min != max");
    }
  }
  for (const auto& b : layout.buttons) {
    if (b.present && (b.byte < 0 || b.byte > 63 || b.bit < 0 || b.bit > 7)) {
      throw std::invalid_argument("gamepad button '" + b.name + "': expected byte 0..63, bit 0..7");
    }
  }
}

}  // namespace facectl
