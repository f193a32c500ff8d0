#include "drivers/protocol/dynamixel_x_table.hpp"

#include <array>

namespace facectl::dxl_x {
namespace {

// Model Numbers and Present Load/Current units from the e-Manual's pages of
// each model ("Model Number", "Present Current"); XL430 and XC430 report
// load, the others current.
constexpr std::array kModels = {
    Model{1000, "XH430-W350", LoadUnit::kCurrent, 2.69},
    Model{1001, "XD430-T350", LoadUnit::kCurrent, 2.69},
    Model{1010, "XH430-W210", LoadUnit::kCurrent, 2.69},
    Model{1011, "XD430-T210", LoadUnit::kCurrent, 2.69},
    Model{1020, "XM430-W350", LoadUnit::kCurrent, 2.69},
    Model{1030, "XM430-W210", LoadUnit::kCurrent, 2.69},
    Model{1040, "XH430-V350", LoadUnit::kCurrent, 1.34},
    Model{1050, "XH430-V210", LoadUnit::kCurrent, 1.34},
    Model{1060, "XL430-W250", LoadUnit::kPermille, 0.0},
    Model{1070, "XC430-W150", LoadUnit::kPermille, 0.0},
    Model{1080, "XC430-W240", LoadUnit::kPermille, 0.0},
    Model{1090, "2XL430-W250", LoadUnit::kPermille, 0.0},
    Model{1100, "XH540-W270", LoadUnit::kCurrent, 2.69},
    Model{1101, "XD540-T270", LoadUnit::kCurrent, 2.69},
    Model{1110, "XH540-W150", LoadUnit::kCurrent, 2.69},
    Model{1111, "XD540-T150", LoadUnit::kCurrent, 2.69},
    Model{1120, "XM540-W270", LoadUnit::kCurrent, 2.69},
    Model{1130, "XM540-W150", LoadUnit::kCurrent, 2.69},
    Model{1140, "XH540-V270", LoadUnit::kCurrent, 2.69},
    Model{1150, "XH540-V150", LoadUnit::kCurrent, 2.69},
    Model{1160, "2XC430-W250", LoadUnit::kPermille, 0.0},
    Model{1170, "XW540-T260", LoadUnit::kCurrent, 2.69},
    Model{1180, "XW540-T140", LoadUnit::kCurrent, 2.69},
    Model{1190, "XL330-M077", LoadUnit::kCurrent, 1.0},
    Model{1200, "XL330-M288", LoadUnit::kCurrent, 1.0},
    Model{1210, "XC330-T181", LoadUnit::kCurrent, 1.0},
    Model{1220, "XC330-T288", LoadUnit::kCurrent, 1.0},
    Model{1230, "XC330-M181", LoadUnit::kCurrent, 1.0},
    Model{1240, "XC330-M288", LoadUnit::kCurrent, 1.0},
    Model{1270, "XW430-T333", LoadUnit::kCurrent, 2.69},
    Model{1280, "XW430-T200", LoadUnit::kCurrent, 2.69},
};

}  // namespace

std::string hardware_error_text(std::uint8_t bits) {
  if (bits == 0) return "none";
  std::string out;
  const auto add = [&](std::uint8_t bit, const char* name) {
    if ((bits & bit) == 0) return;
    if (!out.empty()) out += ", ";
    out += name;
    bits = static_cast<std::uint8_t>(bits & ~bit);
  };
  add(kErrInputVoltage, "input voltage");
  add(kErrOverheating, "overheating");
  add(kErrMotorEncoder, "motor encoder");
  add(kErrElectricalShock, "electrical shock");
  add(kErrOverload, "overload");
  if (bits != 0) {
    if (!out.empty()) out += ", ";
    out += "bits 0x" + std::string(1, "0123456789abcdef"[bits >> 4]) +
           std::string(1, "0123456789abcdef"[bits & 15]);
  }
  return out;
}

const Model* find_model(std::uint16_t number) {
  for (const Model& m : kModels) {
    if (m.number == number) return &m;
  }
  return nullptr;
}

}  // namespace facectl::dxl_x
