#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

// The control table the DYNAMIXEL X series shares under Protocol 2.0
// (ROBOTIS e-Manual, e.g. "XL430-W250" and "XM430-W350", "Control Table"):
// the addresses facectl reads and writes, the models that have this table,
// and what their feedback registers mean. docs/PROTOCOLS.md, "Dynamixel".
namespace facectl::dxl_x {

// EEPROM (written only with torque off).
inline constexpr std::uint16_t kModelNumber = 0;      // 2 bytes
inline constexpr std::uint16_t kFirmwareVersion = 6;  // 1
inline constexpr std::uint16_t kReturnDelayTime = 9;  // 1, unit 2 us
inline constexpr std::uint16_t kOperatingMode = 11;   // 1, 3 = position control
inline constexpr std::uint16_t kTemperatureLimit = 31;
inline constexpr std::uint16_t kMaxPositionLimit = 48;  // 4, pulses
inline constexpr std::uint16_t kMinPositionLimit = 52;  // 4, pulses
// RAM.
inline constexpr std::uint16_t kTorqueEnable = 64;         // 1
inline constexpr std::uint16_t kStatusReturnLevel = 68;    // 1, 2 = answer every instruction
inline constexpr std::uint16_t kHardwareErrorStatus = 70;  // 1, bits below
inline constexpr std::uint16_t kBusWatchdog = 98;          // 1, unit 20 ms; -1 = tripped
inline constexpr std::uint16_t kGoalPosition = 116;        // 4, pulses
inline constexpr std::uint16_t kPresentLoad = 126;      // 2, signed: 0.1 % (load) or a current unit
inline constexpr std::uint16_t kPresentPosition = 132;  // 4, signed pulses
inline constexpr std::uint16_t kPresentInputVoltage = 144;  // 2, 0.1 V
inline constexpr std::uint16_t kPresentTemperature = 146;   // 1, deg C
inline constexpr std::uint16_t kTableEnd = 147;

inline constexpr std::uint8_t kPositionControlMode = 3;
inline constexpr int kBusWatchdogUnitMs = 20;

// The block facectl reads each cycle with one sync read: Present Load
// through Present Temperature.
inline constexpr std::uint16_t kFeedbackAddress = kPresentLoad;
inline constexpr std::uint16_t kFeedbackLength = kPresentTemperature + 1 - kPresentLoad;  // 21

// Bytes on the wire in one I/O cycle of `servos` servos: the Sync Write of
// the goals (14 + 5 n), the Sync Read request (14 + n) and one status
// packet per servo (11 + 21), byte stuffing aside.
constexpr std::size_t cycle_bytes(std::size_t servos) {
  return (14 + 5 * servos) + (14 + servos) + servos * (11 + kFeedbackLength);
}

// Hardware Error Status bits (the "Shutdown" item): the servo has switched
// its torque off by itself and keeps it off until rebooted.
inline constexpr std::uint8_t kErrInputVoltage = 1U << 0;
inline constexpr std::uint8_t kErrOverheating = 1U << 2;
inline constexpr std::uint8_t kErrMotorEncoder = 1U << 3;
inline constexpr std::uint8_t kErrElectricalShock = 1U << 4;
inline constexpr std::uint8_t kErrOverload = 1U << 5;
// "overload, overheating" for the set bits; "none" for 0.
std::string hardware_error_text(std::uint8_t bits);

// What Present Load (126) holds on a model.
enum class LoadUnit {
  kPermille,  // Present Load, 0.1 % of the maximum torque (XL430, XC430)
  kCurrent,   // Present Current, in `current_ma` milliamperes per count
};
struct Model {
  std::uint16_t number = 0;
  const char* name = "";
  LoadUnit load = LoadUnit::kCurrent;
  double current_ma = 0.0;  // per count, for kCurrent
};
// The X-series model with this Model Number, or nullptr: another series
// (MX, PRO, P, the Protocol 1.0 AX) lays its control table out differently.
const Model* find_model(std::uint16_t number);

// Little-endian fields of a control table or a status packet's parameters.
inline std::uint16_t get_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
inline std::int32_t get_i32(const std::uint8_t* p) {
  return static_cast<std::int32_t>(
      static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
      (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24));
}
inline void put_u16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
inline void put_i32(std::uint8_t* p, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(u >> (8 * i));
}

}  // namespace facectl::dxl_x
