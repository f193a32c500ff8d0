#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace facectl::maestro {

// Pololu Maestro serial commands (Pololu Maestro Servo Controller User's
// Guide, https://www.pololu.com/docs/0J40, section 5.e "Serial Servo
// Commands", 5.c "Serial Protocols", 4.e "Errors"; docs/PROTOCOLS.md,
// "Pololu Maestro"). tests/drivers/maestro_serial_test.cpp checks 0x84, 0x87
// and 0x9F against the guide's byte examples, the others against its formats.
// No I/O here: the driver, the doctor and the simulator share these bytes.

// Command bytes of the compact protocol; the Pololu protocol sends the same
// byte with its MSB cleared after 0xAA and the device number (5.c).
constexpr std::uint8_t kSetTarget = 0x84;
constexpr std::uint8_t kSetSpeed = 0x87;
constexpr std::uint8_t kSetAcceleration = 0x89;
constexpr std::uint8_t kGetPosition = 0x90;         // reply: 2 bytes, little-endian
constexpr std::uint8_t kSetMultipleTargets = 0x9F;  // Mini Maestro 12, 18, 24 only
constexpr std::uint8_t kGetErrors = 0xA1;           // reply: 2 bytes; clears the register
constexpr std::uint8_t kPololuStart = 0xAA;
constexpr int kDefaultDeviceNumber = 12;  // 5.c: the factory's device number
constexpr int kMaxTarget = 0x3FFF;        // 14 bits: two 7-bit data bytes
constexpr int kMaxChannels = 24;          // the Mini Maestro 24

// The error register's bits (4.e "Errors").
constexpr std::uint16_t kErrSerialSignal = 1u << 0;
constexpr std::uint16_t kErrSerialOverrun = 1u << 1;
constexpr std::uint16_t kErrSerialRxBufferFull = 1u << 2;
constexpr std::uint16_t kErrSerialCrc = 1u << 3;
constexpr std::uint16_t kErrSerialProtocol = 1u << 4;
constexpr std::uint16_t kErrSerialTimeout = 1u << 5;
constexpr std::uint16_t kErrScriptStack = 1u << 6;
constexpr std::uint16_t kErrScriptCallStack = 1u << 7;
constexpr std::uint16_t kErrScriptProgramCounter = 1u << 8;
constexpr std::uint16_t kKnownErrors = 0x01FF;

enum class Protocol { kCompact, kPololu };

// Who a command goes to: the protocol and, for Pololu, the device number.
struct Addressing {
  Protocol protocol = Protocol::kCompact;
  int device_number = kDefaultDeviceNumber;  // 0..127
};

// Each encoder writes one command into `out` and returns its size, or 0 when
// `out` is too small or an argument is out of range (channel > 127, target
// or speed > 14 bits).
std::size_t encode_set_target(const Addressing& to, int channel, int quarter_us,
                              std::span<std::uint8_t> out);
std::size_t encode_set_speed(const Addressing& to, int channel, int speed,
                             std::span<std::uint8_t> out);
std::size_t encode_set_acceleration(const Addressing& to, int channel, int acceleration,
                                    std::span<std::uint8_t> out);
// Targets for the channels first_channel, first_channel + 1, ...
std::size_t encode_set_multiple_targets(const Addressing& to, int first_channel,
                                        std::span<const std::uint16_t> quarter_us,
                                        std::span<std::uint8_t> out);
std::size_t encode_get_position(const Addressing& to, int channel, std::span<std::uint8_t> out);
std::size_t encode_get_errors(const Addressing& to, std::span<std::uint8_t> out);

// The two-byte replies of Get Position and Get Errors: low byte first.
constexpr std::uint16_t reply_u16(const std::uint8_t* b) {
  return static_cast<std::uint16_t>(b[0] | (b[1] << 8));
}

// The register's bits in words, worst first ("serial timeout, protocol
// error"); "none" for 0.
std::string error_text(std::uint16_t bits);
// The single worst bit of `bits` (0 for none): the one a FAULT names.
std::uint16_t worst_error(std::uint16_t bits);

// Bytes of one I/O cycle: `targets` Set Target commands (or one Set Multiple
// Targets over `span` channels when `multiple`), a Get Position per channel
// and Get Errors, with their replies.
std::size_t cycle_bytes(Protocol protocol, std::size_t channels, bool multiple, std::size_t span);

}  // namespace facectl::maestro
