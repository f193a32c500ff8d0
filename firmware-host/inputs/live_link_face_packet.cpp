#include "firmware-host/inputs/live_link_face_packet.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include "firmware-host/inputs/arkit_blendshapes.hpp"

namespace facectl {
namespace {

// Reads big-endian fields in order; every failure names the byte offset.
class Cursor {
 public:
  explicit Cursor(std::span<const std::uint8_t> b) : b_(b) {}

  std::size_t offset() const { return at_; }
  std::size_t left() const { return b_.size() - at_; }

  [[noreturn]] void fail(std::size_t at, const char* field, const std::string& expected,
                         const std::string& found) const {
    throw LiveLinkFacePacketError("byte " + std::to_string(at) + ": " + field + ": expected " +
                                  expected + ", found " + found);
  }
  void need(std::size_t n, const char* field) const {
    if (left() < n) {
      fail(at_, field, std::to_string(n) + " bytes",
           left() == 0 ? "the end of the datagram" : "only " + std::to_string(left()));
    }
  }
  std::uint8_t u8(const char* field) {
    need(1, field);
    return b_[at_++];
  }
  std::uint32_t u32(const char* field) {
    need(4, field);
    const std::uint32_t v = (std::uint32_t{b_[at_]} << 24) | (std::uint32_t{b_[at_ + 1]} << 16) |
                            (std::uint32_t{b_[at_ + 2]} << 8) | std::uint32_t{b_[at_ + 3]};
    at_ += 4;
    return v;
  }
  std::int32_t i32(const char* field) { return static_cast<std::int32_t>(u32(field)); }
  float f32(const char* field) {
    const std::uint32_t bits = u32(field);
    float v = 0;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  // An i32 length, then that many bytes.
  std::string_view text(const char* field) {
    const std::size_t at = at_;
    const std::int32_t n = i32(field);
    if (n < 0 || static_cast<std::size_t>(n) > kLiveLinkFaceMaxName) {
      fail(at, field, "a length 0.." + std::to_string(kLiveLinkFaceMaxName), std::to_string(n));
    }
    need(static_cast<std::size_t>(n), field);
    const std::string_view s(reinterpret_cast<const char*>(b_.data() + at_),
                             static_cast<std::size_t>(n));
    at_ += static_cast<std::size_t>(n);
    return s;
  }

 private:
  std::span<const std::uint8_t> b_;
  std::size_t at_ = 0;
};

// Unreal's EARFaceBlendShape order (ARTypes.h), as Live Link Face sends it.
constexpr std::array<std::string_view, kArkitCount> kPacketOrder = {
    "eyeBlinkLeft",      "eyeLookDownLeft",    "eyeLookInLeft",
    "eyeLookOutLeft",    "eyeLookUpLeft",      "eyeSquintLeft",
    "eyeWideLeft",       "eyeBlinkRight",      "eyeLookDownRight",
    "eyeLookInRight",    "eyeLookOutRight",    "eyeLookUpRight",
    "eyeSquintRight",    "eyeWideRight",       "jawForward",
    "jawLeft",           "jawRight",           "jawOpen",
    "mouthClose",        "mouthFunnel",        "mouthPucker",
    "mouthLeft",         "mouthRight",         "mouthSmileLeft",
    "mouthSmileRight",   "mouthFrownLeft",     "mouthFrownRight",
    "mouthDimpleLeft",   "mouthDimpleRight",   "mouthStretchLeft",
    "mouthStretchRight", "mouthRollLower",     "mouthRollUpper",
    "mouthShrugLower",   "mouthShrugUpper",    "mouthPressLeft",
    "mouthPressRight",   "mouthLowerDownLeft", "mouthLowerDownRight",
    "mouthUpperUpLeft",  "mouthUpperUpRight",  "browDownLeft",
    "browDownRight",     "browInnerUp",        "browOuterUpLeft",
    "browOuterUpRight",  "cheekPuff",          "cheekSquintLeft",
    "cheekSquintRight",  "noseSneerLeft",      "noseSneerRight",
    "tongueOut"};

std::array<std::size_t, kArkitCount> packet_to_arkit() {
  std::array<std::size_t, kArkitCount> map{};
  for (std::size_t i = 0; i < kArkitCount; ++i) map[i] = *find_arkit(kPacketOrder[i]);
  return map;
}

}  // namespace

std::size_t live_link_face_arkit_index(std::size_t packet_index) {
  static const std::array<std::size_t, kArkitCount> map = packet_to_arkit();
  return map.at(packet_index);
}

LiveLinkFacePacket parse_live_link_face_packet(std::span<const std::uint8_t> bytes) {
  Cursor c(bytes);
  LiveLinkFacePacket p;
  const std::uint8_t version = c.u8("packet version");
  if (version != kLiveLinkFaceVersion) {
    c.fail(0, "packet version", std::to_string(kLiveLinkFaceVersion), std::to_string(version));
  }
  p.device_id = c.text("device id");
  p.subject = c.text("subject name");
  if (c.left() == 0) return p;  // no face tracked
  p.frame = c.i32("frame number");
  p.subframe = c.f32("subframe");
  p.rate_numerator = c.i32("frame rate numerator");
  p.rate_denominator = c.i32("frame rate denominator");
  const std::size_t count_at = c.offset();
  const std::uint8_t count = c.u8("blendshape count");
  if (count != kLiveLinkFaceValues) {
    c.fail(count_at, "blendshape count", std::to_string(kLiveLinkFaceValues),
           std::to_string(count));
  }
  for (std::size_t i = 0; i < kLiveLinkFaceValues; ++i) {
    const std::size_t at = c.offset();
    const bool weight = i < kArkitCount;
    const char* field = weight ? "blendshape weight" : "rotation";
    const float v = c.f32(field);
    if (!std::isfinite(v)) c.fail(at, field, "a finite number", "NaN or infinity");
    if (weight ? (v < kLiveLinkFaceMinWeight || v > kLiveLinkFaceMaxWeight)
               : std::abs(v) > static_cast<float>(M_PI)) {
      c.fail(at, field, weight ? "-0.5..1.5" : "radians within -pi..pi", std::to_string(v));
    }
    p.values[i] = v;
  }
  if (c.left() != 0) {
    c.fail(c.offset(), "end of packet", "the end of the datagram",
           std::to_string(c.left()) + " more bytes");
  }
  p.has_face = true;
  return p;
}

}  // namespace facectl
