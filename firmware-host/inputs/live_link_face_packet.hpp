#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string_view>

namespace facectl {

// One datagram of the Live Link Face app's UDP stream, packet version 6
// (docs/INPUTS.md, "Live Link Face stream"). Every field is big-endian:
//
//   u8 version (6) | i32 n, n bytes device id | i32 n, n bytes subject name |
//   i32 frame, f32 subframe, i32 rate numerator, i32 rate denominator |
//   u8 count (61) | count x f32: the 52 blendshapes in Unreal's
//   EARFaceBlendShape order, then head yaw, pitch, roll and each eye's yaw,
//   pitch, roll (radians)
//
// A packet that ends after the subject name carries no face (the app sends
// these while it tracks none).
inline constexpr std::uint8_t kLiveLinkFaceVersion = 6;
inline constexpr std::size_t kLiveLinkFaceValues = 61;
inline constexpr std::size_t kLiveLinkFaceMaxName = 256;  // Unreal's bound on either string
inline constexpr double kLiveLinkFaceMinWeight = -0.5;
inline constexpr double kLiveLinkFaceMaxWeight = 1.5;
// 52 blendshapes then these.
inline constexpr std::size_t kLiveLinkFaceHeadYaw = 52;

struct LiveLinkFacePacket {
  std::string_view device_id;  // into the datagram
  std::string_view subject;
  bool has_face = false;
  std::int32_t frame = 0;
  float subframe = 0;
  std::int32_t rate_numerator = 0, rate_denominator = 0;
  std::array<float, kLiveLinkFaceValues> values{};
};

// A datagram that is not a version 6 packet. The message names the byte
// offset and the field: "byte 41: subject name length: expected 0..256, found -3".
class LiveLinkFacePacketError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads one datagram (allocating only to report a failure). Strict where a
// value would be played, with the Live Link Face CSV's bounds: the count must
// be 61, each blendshape weight within -0.5..1.5 (ARKit's solver overshoots
// 0..1 a little; the stream clamps it), each rotation within -pi..pi, and the
// packet must end after the last value. The frame time is not checked (the
// stream plays on arrival, and some senders write a rate denominator of 0).
LiveLinkFacePacket parse_live_link_face_packet(std::span<const std::uint8_t> bytes);

// Packet index (0..51) -> index into kArkitNames: Unreal's order puts
// jawLeft before jawRight and mouthLeft before mouthRight; the CSV does not.
std::size_t live_link_face_arkit_index(std::size_t packet_index);

}  // namespace facectl
