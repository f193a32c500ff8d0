#include "drivers/protocol/custom_can_frames.hpp"

#include <algorithm>
#include <stdexcept>

namespace facectl::custom_can {

namespace {
ActuatorKind kind_of(modbus_map::Unit unit) {
  return unit == modbus_map::Unit::kRotary ? ActuatorKind::kRotary : ActuatorKind::kLinear;
}
}  // namespace

WireEncoding field_encoding(ActuatorKind kind, const ActuatorEncoding& encoding, Width width) {
  if (width == Width::kInt16 && encoding.raw == ActuatorEncoding::Raw::kInt32) {
    throw std::invalid_argument(
        "custom CAN: raw int32 does not fit a 2-byte (values: int16) field");
  }
  return WireEncoding(kind, encoding);
}

std::int32_t to_field(const WireEncoding& encoding, double si) {
  return static_cast<std::int32_t>(
      encoding.encode(si));  // uint16 fits; 2-byte fields keep its bits
}

double from_field(const WireEncoding& encoding, Width width, std::int32_t field) {
  return width == Width::kInt16 ? encoding.decode_u16(static_cast<std::uint16_t>(field))
                                : encoding.decode(field);
}

ActuatorEncoding default_encoding(Width width) {
  if (width == Width::kInt16) return {};
  return {ActuatorEncoding::Raw::kInt32, 10000.0, 0.0};
}

std::int32_t to_counts(modbus_map::Unit unit, Width width, double si) {
  return to_field(WireEncoding(kind_of(unit), default_encoding(width)), si);
}

double from_counts(modbus_map::Unit unit, Width width, std::int32_t counts) {
  return from_field(WireEncoding(kind_of(unit), default_encoding(width)), width, counts);
}

int channels_per_frame(bool fd, Width width) {
  return ((fd ? 64 : 8) - 2) / static_cast<int>(width);
}

void encode_command(const Command& c, Width width, std::span<const std::int32_t> targets, bool fd,
                    CanFrame& out) {
  const auto w = static_cast<std::size_t>(width);
  out.id = kCommandBase + static_cast<std::uint32_t>(c.node);
  out.fd = fd;
  out.data[0] = c.sequence;
  out.data[1] = c.flags;
  std::size_t n = 0;
  for (; n < targets.size() && n < static_cast<std::size_t>(channels_per_frame(fd, width)); ++n) {
    const std::int32_t v = targets[n];
    std::uint8_t* p = &out.data[2 + n * w];
    if (width == Width::kInt16) {
      put_u16(p, static_cast<std::uint16_t>(static_cast<std::int16_t>(v)));
    } else {
      put_u32(p, static_cast<std::uint32_t>(v));
    }
  }
  std::size_t len = 2 + n * w;
  if (fd && len > 8) {
    // CAN FD carries 12, 16, 20, 24, 32, 48 or 64 bytes above 8: pad with zeros.
    std::size_t padded = 64;
    for (std::size_t size : {12, 16, 20, 24, 32, 48}) {
      if (len <= size) {
        padded = size;
        break;
      }
    }
    std::fill(out.data.begin() + static_cast<std::ptrdiff_t>(len),
              out.data.begin() + static_cast<std::ptrdiff_t>(padded), 0);
    len = padded;
  }
  out.len = static_cast<std::uint8_t>(len);
}

std::optional<Feedback> decode_feedback(const CanFrame& f, Width width) {
  const auto w = static_cast<std::size_t>(width);
  if (f.id <= kFeedbackBase || f.id > kFeedbackBase + 63) return std::nullopt;
  // Classic frames carry exactly whole channels; FD frames may be padded.
  if (f.len < 2 || (!f.fd && (f.len - 2) % w != 0)) return std::nullopt;
  Feedback fb;
  fb.node = static_cast<int>(f.id - kFeedbackBase);
  fb.sequence_echo = f.data[0];
  fb.status = f.data[1];
  fb.channels = static_cast<int>((f.len - 2) / w);
  if (fb.channels > static_cast<int>(fb.positions.size())) return std::nullopt;
  for (std::size_t i = 0; i < static_cast<std::size_t>(fb.channels); ++i) {
    const std::uint8_t* p = &f.data[2 + i * w];
    const std::int32_t v = width == Width::kInt16 ? static_cast<std::int16_t>(get_u16(p))
                                                  : static_cast<std::int32_t>(get_u32(p));
    fb.positions[i] = v;
  }
  return fb;
}

}  // namespace facectl::custom_can
