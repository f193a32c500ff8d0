#include "drivers/protocol/cia402_counts.hpp"

#include <cmath>
#include <stdexcept>

#include "control/units.hpp"

namespace facectl::cia402 {

std::int32_t DriveCounts::encode(double si) const {
  double c = std::nearbyint(si * per_si + offset);
  if (!(c >= -2147483647.0)) c = -2147483647.0;
  if (c > 2147483647.0) c = 2147483647.0;
  return static_cast<std::int32_t>(c);
}

DriveCounts drive_counts(const ActuatorModel& a, const CanBusOptions& bus) {
  const bool rotary = a.kind == ActuatorKind::kRotary;
  const ActuatorEncoding& e = a.encoding;
  if (e.raw == ActuatorEncoding::Raw::kInt32) {
    // Scale is per deg or mm; the drive works in SI (rad, m).
    return {e.scale * (rotary ? kDegPerRad : 1e3), e.offset};
  }
  const ActuatorEncoding none;  // what an actuator without `encoding` carries
  if (e.raw != none.raw || e.scale != none.scale || e.offset != none.offset) {
    throw std::invalid_argument("actuator " + a.name +
                                ": a CiA 402 drive counts in raw int32, not 16 bits");
  }
  return {rotary ? bus.rotary_counts_per_rad : bus.linear_counts_per_m, 0.0};
}

}  // namespace facectl::cia402
