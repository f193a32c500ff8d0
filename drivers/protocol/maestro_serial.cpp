#include "drivers/protocol/maestro_serial.hpp"

#include <cstdio>

namespace facectl::maestro {
namespace {

// The command's first bytes: 0x84 alone (compact), or 0xAA, the device
// number and 0x04, the command with its MSB cleared (Pololu; guide 5.c).
std::size_t header(const Addressing& to, std::uint8_t command, std::span<std::uint8_t> out) {
  if (to.protocol == Protocol::kCompact) {
    if (out.empty()) return 0;
    out[0] = command;
    return 1;
  }
  if (out.size() < 3 || to.device_number < 0 || to.device_number > 127) return 0;
  out[0] = kPololuStart;
  out[1] = static_cast<std::uint8_t>(to.device_number);
  out[2] = static_cast<std::uint8_t>(command & 0x7F);
  return 3;
}

// A 14-bit value as two data bytes of 7 bits, low first (guide 5.e, Set Target).
void put14(std::uint8_t* p, int v) {
  p[0] = static_cast<std::uint8_t>(v & 0x7F);
  p[1] = static_cast<std::uint8_t>((v >> 7) & 0x7F);
}

std::size_t channel_value(const Addressing& to, std::uint8_t command, int channel, int value,
                          std::span<std::uint8_t> out) {
  if (channel < 0 || channel > 127 || value < 0 || value > kMaxTarget) return 0;
  const std::size_t h = header(to, command, out);
  if (h == 0 || out.size() < h + 3) return 0;
  out[h] = static_cast<std::uint8_t>(channel);
  put14(&out[h + 1], value);
  return h + 3;
}

}  // namespace

std::size_t encode_set_target(const Addressing& to, int channel, int quarter_us,
                              std::span<std::uint8_t> out) {
  return channel_value(to, kSetTarget, channel, quarter_us, out);
}

std::size_t encode_set_speed(const Addressing& to, int channel, int speed,
                             std::span<std::uint8_t> out) {
  return channel_value(to, kSetSpeed, channel, speed, out);
}

std::size_t encode_set_acceleration(const Addressing& to, int channel, int acceleration,
                                    std::span<std::uint8_t> out) {
  return channel_value(to, kSetAcceleration, channel, acceleration, out);
}

std::size_t encode_set_multiple_targets(const Addressing& to, int first_channel,
                                        std::span<const std::uint16_t> quarter_us,
                                        std::span<std::uint8_t> out) {
  // 0x9F, number of targets, first channel, then each target as in Set Target.
  if (quarter_us.empty() || quarter_us.size() > 127 || first_channel < 0 || first_channel > 127) {
    return 0;
  }
  const std::size_t h = header(to, kSetMultipleTargets, out);
  const std::size_t n = h + 2 + 2 * quarter_us.size();
  if (h == 0 || out.size() < n) return 0;
  out[h] = static_cast<std::uint8_t>(quarter_us.size());
  out[h + 1] = static_cast<std::uint8_t>(first_channel);
  for (std::size_t i = 0; i < quarter_us.size(); ++i) {
    if (quarter_us[i] > kMaxTarget) return 0;
    put14(&out[h + 2 + 2 * i], quarter_us[i]);
  }
  return n;
}

std::size_t encode_get_position(const Addressing& to, int channel, std::span<std::uint8_t> out) {
  if (channel < 0 || channel > 127) return 0;
  const std::size_t h = header(to, kGetPosition, out);
  if (h == 0 || out.size() < h + 1) return 0;
  out[h] = static_cast<std::uint8_t>(channel);
  return h + 1;
}

std::size_t encode_get_errors(const Addressing& to, std::span<std::uint8_t> out) {
  return header(to, kGetErrors, out);
}

namespace {

// Worst first: a serial timeout means the Maestro already sent its servos
// home; script errors mean a script is fighting the host for the outputs.
struct Bit {
  std::uint16_t bit;
  const char* text;
};
constexpr Bit kBits[] = {
    {kErrSerialTimeout, "serial timeout"},
    {kErrSerialSignal, "serial signal error (baud rate?)"},
    {kErrSerialOverrun, "serial overrun"},
    {kErrSerialRxBufferFull, "serial RX buffer full"},
    {kErrSerialCrc, "serial CRC error"},
    {kErrSerialProtocol, "serial protocol error"},
    {kErrScriptStack, "script stack error"},
    {kErrScriptCallStack, "script call stack error"},
    {kErrScriptProgramCounter, "script program counter error"},
};

}  // namespace

std::uint16_t worst_error(std::uint16_t bits) {
  for (const Bit& b : kBits) {
    if ((bits & b.bit) != 0) return b.bit;
  }
  return bits == 0 ? 0 : static_cast<std::uint16_t>(bits & (~bits + 1));  // an unknown bit
}

std::string error_text(std::uint16_t bits) {
  if (bits == 0) return "none";
  std::string s;
  for (const Bit& b : kBits) {
    if ((bits & b.bit) == 0) continue;
    if (!s.empty()) s += ", ";
    s += b.text;
  }
  if ((bits & ~kKnownErrors) != 0) {
    if (!s.empty()) s += ", ";
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%04x", bits & ~kKnownErrors);
    s += std::string("unknown bits ") + hex;
  }
  return s;
}

std::size_t cycle_bytes(Protocol protocol, std::size_t channels, bool multiple, std::size_t span) {
  const std::size_t h = protocol == Protocol::kCompact ? 1 : 3;
  const std::size_t targets = multiple ? h + 2 + 2 * span : channels * (h + 3);
  // Get Position per channel (header, channel; 2 back), Get Errors (2 back).
  return targets + channels * (h + 1 + 2) + h + 2;
}

}  // namespace facectl::maestro
