#include "drivers/protocol/wire_encoding.hpp"

#include <cmath>

#include "control/units.hpp"

namespace facectl {

double raw_min(ActuatorEncoding::Raw raw) {
  switch (raw) {
    case ActuatorEncoding::Raw::kUint16:
      return 0.0;
    case ActuatorEncoding::Raw::kInt32:
      return -2147483647.0;
    default:
      return -32767.0;  // symmetric, as the drivers always saturated
  }
}

double raw_max(ActuatorEncoding::Raw raw) {
  switch (raw) {
    case ActuatorEncoding::Raw::kUint16:
      return 65535.0;
    case ActuatorEncoding::Raw::kInt32:
      return 2147483647.0;
    default:
      return 32767.0;
  }
}

const char* raw_name(ActuatorEncoding::Raw raw) {
  switch (raw) {
    case ActuatorEncoding::Raw::kUint16:
      return "uint16";
    case ActuatorEncoding::Raw::kInt32:
      return "int32";
    default:
      return "int16";
  }
}

WireEncoding::WireEncoding(ActuatorKind kind, const ActuatorEncoding& encoding)
    : raw_(encoding.raw),
      // Written as (1/scale) · unit so the default (100 counts per deg or mm)
      // gives bit for bit the step the drivers used before: 0.01 · π / 180.
      si_per_count_(kind == ActuatorKind::kRotary ? (1.0 / encoding.scale) * kPi / 180.0
                                                  : (1.0 / encoding.scale) * 1e-3),
      offset_(encoding.offset),
      min_(raw_min(encoding.raw)),
      max_(raw_max(encoding.raw)) {}

std::int64_t WireEncoding::encode(double si) const {
  double raw = std::nearbyint(si / si_per_count_ + offset_);
  if (!(raw >= min_)) raw = min_;  // also catches NaN: saturate low, never wrap
  if (raw > max_) raw = max_;
  return static_cast<std::int64_t>(raw);
}

double WireEncoding::decode(std::int64_t raw) const {
  return (static_cast<double>(raw) - offset_) * si_per_count_;
}

double WireEncoding::decode_u16(std::uint16_t word) const {
  return decode(raw_ == ActuatorEncoding::Raw::kUint16 ? static_cast<std::int64_t>(word)
                                                       : static_cast<std::int16_t>(word));
}

}  // namespace facectl
