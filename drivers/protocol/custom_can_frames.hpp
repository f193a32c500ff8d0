#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "drivers/protocol/can_frame.hpp"
#include "drivers/protocol/modbus_register_map.hpp"
#include "drivers/protocol/wire_encoding.hpp"

// facectl's frame layout for custom actuator boards (docs/PROTOCOLS.md,
// "CAN: custom boards"), in the style of ODrive's CANSimple and moteus:
// several actuators per frame, a sequence counter, and the board's feedback
// frame doubling as its heartbeat. Little-endian, like CANopen.
namespace facectl::custom_can {

inline constexpr std::uint32_t kCommandBase = 0x100;   // + node (1..63): host -> board
inline constexpr std::uint32_t kFeedbackBase = 0x180;  // + node: board -> host, also its heartbeat

inline constexpr std::uint8_t kFlagEnable = 0x01;
inline constexpr std::uint8_t kFlagFaultReset = 0x02;
inline constexpr std::uint8_t kStatusEnabled = 0x01;
inline constexpr std::uint8_t kStatusFault = 0x02;
inline constexpr std::uint8_t kStatusWatchdog = 0x04;

enum class Width : std::uint8_t { kInt16 = 2, kInt32 = 4 };

// Each channel's field carries its actuator's encoding (WireEncoding). A
// 2-byte field takes raw int16 or uint16, a 4-byte field any raw type.
// Throws std::invalid_argument for raw int32 in a 2-byte field (the rig
// loader refuses it first, naming file:line:col).
WireEncoding field_encoding(ActuatorKind kind, const ActuatorEncoding& encoding, Width width);
// A field's value (as encode_command takes it) and back to SI; a 2-byte
// field is read per the raw type (int16 sign-extends, uint16 not).
std::int32_t to_field(const WireEncoding& encoding, double si);
double from_field(const WireEncoding& encoding, Width width, std::int32_t field);

// The encoding of a field whose actuator names none: int16 counts of 0.01
// degree / 0.01 mm; int32 counts of 0.0001 degree / 0.0001 mm.
ActuatorEncoding default_encoding(Width width);
std::int32_t to_counts(modbus_map::Unit unit, Width width, double si);
double from_counts(modbus_map::Unit unit, Width width, std::int32_t counts);

// Channels that fit one frame: (payload - 2) / width.
int channels_per_frame(bool fd, Width width);

struct Command {
  int node = 0;
  std::uint8_t sequence = 0;
  std::uint8_t flags = 0;
};
// Writes a command frame: [seq][flags][value 0]...[value n-1]; a CAN FD frame
// longer than 8 bytes is zero-padded to the next valid FD length.
// Each channel's unit may differ, so values arrive already in counts (to_counts).
void encode_command(const Command& c, Width width, std::span<const std::int32_t> targets, bool fd,
                    CanFrame& out);

struct Feedback {
  int node = 0;
  std::uint8_t sequence_echo = 0;
  std::uint8_t status = 0;
  int channels = 0;
  std::array<std::int32_t, 31> positions{};  // counts (from_counts)
};
// Decodes a feedback frame; nullopt when `f` is not a feedback frame or a
// classic frame's length is not 2 + k·width (the caller counts it as a bad
// frame). A padded FD frame decodes to every whole channel it holds; the
// caller uses the ones it has.
std::optional<Feedback> decode_feedback(const CanFrame& f, Width width);

}  // namespace facectl::custom_can
