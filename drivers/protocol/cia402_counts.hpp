#pragma once

#include <cstdint>

#include "control/actuator_model.hpp"
#include "drivers/can/can_bus_options.hpp"

namespace facectl::cia402 {

// A drive's position counts (target 0x607A, actual 0x6064, limits 0x607D):
// raw = round(si · per_si + offset), saturating at ±(2^31 − 1), never
// wrapping (NaN goes low). Shared by the bus driver and the simulated drive
// so that both count alike.
struct DriveCounts {
  double per_si = 1.0;  // counts per rad or per m
  double offset = 0.0;  // counts at position 0
  std::int32_t encode(double si) const;
  double decode(std::int32_t raw) const { return (static_cast<double>(raw) - offset) / per_si; }
};

// An actuator's counts: its own `encoding` when it has one (raw int32, scale
// in counts per deg or mm, offset in counts: gear ratio, encoder resolution
// and home offset differ per axis), else the bus's counts_per_rev /
// counts_per_mm with no offset. An encoding with a 16-bit raw type is
// refused: a drive counts in 32 bits (std::invalid_argument).
DriveCounts drive_counts(const ActuatorModel& actuator, const CanBusOptions& bus);

}  // namespace facectl::cia402
