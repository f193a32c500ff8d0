#pragma once

#include <cstddef>
#include <cstdint>

// The Feetech control table items facectl uses (docs/PROTOCOLS.md,
// "Feetech"). Addresses from Feetech's SDK headers: SMS_STS.h (STS series,
// e.g. STS3215; ftservo/FTServo_stm32HAL SCSLib/SMS_STS.h) and SCSCL.h (SCS
// series, e.g. SCS0009/SCS15; FTServo SCSCL.h); Return Delay (7) and
// Response Level (8) from Waveshare's ST servo SMS_STS.h. Both series share
// the addresses except Lock; they differ in byte order (SCS.cpp Host2SCS:
// STS little-endian, SCS big-endian) and range (4096 vs 1024 steps a turn).
namespace facectl::ft {

enum class Series { kSts, kScs };

inline constexpr std::uint8_t kModel = 3;  // 2 bytes, read-only
inline constexpr std::uint8_t kId = 5;
inline constexpr std::uint8_t kBaudRate = 6;
inline constexpr std::uint8_t kReturnDelay = 7;     // unit 2 us
inline constexpr std::uint8_t kResponseLevel = 8;   // 0: answer PING/READ only, 1: all
inline constexpr std::uint8_t kMinAngleLimit = 9;   // 2 bytes
inline constexpr std::uint8_t kMaxAngleLimit = 11;  // 2 bytes
inline constexpr std::uint8_t kTorqueEnable = 40;
inline constexpr std::uint8_t kGoalPosition = 42;  // 2 bytes, then Goal Time, Goal Speed
inline constexpr std::uint8_t kGoalTime = 44;
inline constexpr std::uint8_t kGoalSpeed = 46;
inline constexpr std::uint8_t kLockSts = 55;  // EEPROM write protection: 0 open, 1 locked
inline constexpr std::uint8_t kLockScs = 48;
inline constexpr std::uint8_t kPresentPosition = 56;     // 2 bytes
inline constexpr std::uint8_t kPresentSpeed = 58;        // 2 bytes, sign bit 15
inline constexpr std::uint8_t kPresentLoad = 60;         // 2 bytes, sign bit 10, 0.1 % units
inline constexpr std::uint8_t kPresentVoltage = 62;      // 0.1 V
inline constexpr std::uint8_t kPresentTemperature = 63;  // deg C
inline constexpr std::uint8_t kMoving = 66;
inline constexpr std::uint8_t kPresentCurrent = 69;  // 2 bytes
inline constexpr std::uint8_t kTableEnd = 71;

// What each cycle reads: position, speed, load, voltage, temperature.
inline constexpr std::uint8_t kFeedbackAddress = kPresentPosition;
inline constexpr std::uint8_t kFeedbackLength = 8;

// The status packet's error byte (SCServo SDK protocol_packet_handler.py
// ERRBIT_*): the servo's protection flags.
inline constexpr std::uint8_t kErrVoltage = 0x01;
inline constexpr std::uint8_t kErrAngle = 0x02;  // angle sensor
inline constexpr std::uint8_t kErrOverheat = 0x04;
inline constexpr std::uint8_t kErrOverCurrent = 0x08;
inline constexpr std::uint8_t kErrOverload = 0x20;
const char* error_text(std::uint8_t bit);  // of one bit

inline std::uint8_t lock_address(Series s) {
  return s == Series::kSts ? kLockSts : kLockScs;
}
// Steps a turn: the position range is 0..steps-1.
inline int steps_per_turn(Series s) {
  return s == Series::kSts ? 4096 : 1024;
}

inline std::uint16_t get_u16(Series s, const std::uint8_t* p) {
  return s == Series::kSts ? static_cast<std::uint16_t>(p[0] | p[1] << 8)
                           : static_cast<std::uint16_t>(p[0] << 8 | p[1]);
}
inline void put_u16(Series s, std::uint8_t* p, std::uint16_t v) {
  const auto lo = static_cast<std::uint8_t>(v & 0xFF);
  const auto hi = static_cast<std::uint8_t>(v >> 8);
  p[0] = s == Series::kSts ? lo : hi;
  p[1] = s == Series::kSts ? hi : lo;
}
// Sign-magnitude, as the SDK's ReadSpeed (bit 15) and ReadLoad (bit 10).
inline int sign_magnitude(std::uint16_t raw, int sign_bit) {
  const int magnitude = raw & ((1 << sign_bit) - 1);
  return (raw & (1 << sign_bit)) != 0 ? -magnitude : magnitude;
}
inline std::uint16_t to_sign_magnitude(int v, int sign_bit) {
  return static_cast<std::uint16_t>(v < 0 ? (-v) | (1 << sign_bit) : v);
}

// Bytes on the wire of one I/O cycle for `servos` servos: a sync write of
// goal positions and the feedback (a sync read on STS, one read per servo
// on SCS) with its status packets.
std::size_t cycle_bytes(Series s, std::size_t servos);

}  // namespace facectl::ft
