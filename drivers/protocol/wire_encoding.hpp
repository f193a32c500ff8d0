#pragma once

#include <cstdint>

#include "control/actuator_model.hpp"

namespace facectl {

// An actuator's position on the wire (ActuatorEncoding): raw = round(value ·
// scale + offset) with value in deg or mm, here taken from and returned in SI.
// Shared by the bus drivers and their simulated peers so both sides agree.
class WireEncoding {
 public:
  WireEncoding() = default;
  WireEncoding(ActuatorKind kind, const ActuatorEncoding& encoding);

  // Saturates at the raw type's limits, never wraps (NaN goes to the low
  // limit): int16 ±32767, uint16 0..65535, int32 ±2147483647.
  std::int64_t encode(double si) const;
  double decode(std::int64_t raw) const;

  // The raw value as the 16-bit word a register or int16 field carries.
  std::uint16_t encode_u16(double si) const { return static_cast<std::uint16_t>(encode(si)); }
  // Reads a 16-bit word back per the raw type (int16 sign-extends, uint16 not).
  double decode_u16(std::uint16_t word) const;

  ActuatorEncoding::Raw raw() const { return raw_; }

 private:
  ActuatorEncoding::Raw raw_ = ActuatorEncoding::Raw::kInt16;
  double si_per_count_ = 0.0;
  double offset_ = 0.0;
  double min_ = -32767.0;
  double max_ = 32767.0;
};

// Lowest and highest raw value the type carries (the saturation limits).
double raw_min(ActuatorEncoding::Raw raw);
double raw_max(ActuatorEncoding::Raw raw);
const char* raw_name(ActuatorEncoding::Raw raw);

}  // namespace facectl
