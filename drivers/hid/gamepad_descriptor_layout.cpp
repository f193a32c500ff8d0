#include "drivers/hid/gamepad_descriptor_layout.hpp"

#include <cstdio>
#include <stdexcept>

namespace facectl {
namespace {

// HID Usage Tables 1.4: Generic Desktop (page 1) and its application usages,
// axes 0x30..0x38 and the hat switch 0x39; Simulation Controls (page 2)
// Accelerator 0xC4 and Brake 0xC5; the Button page (9).
constexpr std::uint16_t kGenericDesktop = 0x01, kSimulation = 0x02, kButtonPage = 0x09;
constexpr std::uint16_t kJoystick = 0x04, kGamePad = 0x05, kMultiAxis = 0x08;
constexpr std::uint16_t kX = 0x30, kWheel = 0x38, kHatSwitch = 0x39;
constexpr std::uint16_t kAccelerator = 0xC4, kBrake = 0xC5;
constexpr std::size_t kHatXSlot = 9, kHatYSlot = 10, kAcceleratorSlot = 11, kBrakeSlot = 12;

bool is_gamepad_application(std::uint32_t app) {
  return app == (kGenericDesktop << 16 | kJoystick) || app == (kGenericDesktop << 16 | kGamePad) ||
         app == (kGenericDesktop << 16 | kMultiAxis);
}

GamepadLayout::Axis axis_at(const HidInputField& f, GamepadLayout::Kind kind, const char* name) {
  GamepadLayout::Axis a;
  a.name = name;
  a.byte = f.bit_offset / 8;
  a.bit = f.bit_offset % 8;
  a.bits = f.bit_size;
  a.is_signed = f.logical_min < 0;
  a.min = f.logical_min;
  a.max = f.logical_max;
  a.kind = kind;
  return a;
}

}  // namespace

std::string descriptor_button_name(int usage) {
  return "button_" + std::to_string(usage);
}

GamepadLayout gamepad_layout_from_fields(const std::vector<HidInputField>& fields) {
  const HidInputField* first = nullptr;
  for (const auto& f : fields) {
    if (is_gamepad_application(f.application) && f.is_variable) {
      first = &f;
      break;
    }
  }
  if (first == nullptr) {
    throw std::invalid_argument(
        "HID report descriptor: expected a Joystick, Game Pad or Multi-axis Controller "
        "collection with input fields");
  }
  GamepadLayout l;
  l.report_id = first->report_id;
  for (const char* name : kDescriptorAxisNames) {
    GamepadLayout::Axis a;
    a.name = name;
    a.present = false;
    l.axes.push_back(a);
  }
  for (int b = 1; b <= kDescriptorButtons; ++b) {
    GamepadLayout::Button button;
    button.name = descriptor_button_name(b);
    button.present = false;
    l.buttons.push_back(button);
  }
  for (const auto& f : fields) {
    if (f.report_id != l.report_id || f.application != first->application || !f.is_variable ||
        f.bit_offset + f.bit_size > 64 * 8 || f.logical_min >= f.logical_max) {
      continue;
    }
    auto place = [&](std::size_t slot, GamepadLayout::Kind kind) {
      if (!l.axes[slot].present) l.axes[slot] = axis_at(f, kind, kDescriptorAxisNames[slot]);
    };
    if (f.page == kGenericDesktop && f.usage >= kX && f.usage <= kWheel) {
      place(f.usage - kX, GamepadLayout::Kind::kLinear);
    } else if (f.page == kGenericDesktop && f.usage == kHatSwitch) {
      place(kHatXSlot, GamepadLayout::Kind::kHatX);
      place(kHatYSlot, GamepadLayout::Kind::kHatY);
    } else if (f.page == kSimulation && f.usage == kAccelerator) {
      place(kAcceleratorSlot, GamepadLayout::Kind::kLinear);
    } else if (f.page == kSimulation && f.usage == kBrake) {
      place(kBrakeSlot, GamepadLayout::Kind::kLinear);
    } else if (f.page == kButtonPage && f.usage >= 1 && f.usage <= kDescriptorButtons &&
               f.bit_size == 1) {
      auto& b = l.buttons[f.usage - 1u];
      if (!b.present) {
        b.byte = f.bit_offset / 8;
        b.bit = f.bit_offset % 8;
        b.present = true;
      }
    }
  }
  validate(l);
  return l;
}

GamepadLayout gamepad_layout_from_descriptor(std::span<const std::uint8_t> descriptor) {
  return gamepad_layout_from_fields(parse_hid_descriptor(descriptor));
}

std::string describe(const GamepadLayout& layout) {
  std::string out;
  char line[160];
  if (layout.report_id >= 0) {
    std::snprintf(line, sizeof line, "report id %d (offsets count from the byte after it)\n",
                  layout.report_id);
  } else {
    std::snprintf(line, sizeof line, "no report id\n");
  }
  out += line;
  for (const auto& a : layout.axes) {
    if (!a.present) continue;
    const char* kind = a.kind == GamepadLayout::Kind::kLinear ? "" : " hat";
    std::snprintf(line, sizeof line, "axis   %-12s byte %2d bit %d, %2d bits %s, %g..%g%s\n",
                  a.name.c_str(), a.byte, a.bit, a.bits, a.is_signed ? "signed" : "unsigned", a.min,
                  a.max, kind);
    out += line;
  }
  for (const auto& b : layout.buttons) {
    if (!b.present) continue;
    std::snprintf(line, sizeof line, "button %-12s byte %2d bit %d\n", b.name.c_str(), b.byte,
                  b.bit);
    out += line;
  }
  return out;
}

}  // namespace facectl
