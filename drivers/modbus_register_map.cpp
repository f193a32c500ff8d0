#include "drivers/modbus_register_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace facectl::modbus_map {

namespace {
constexpr double kPi = 3.14159265358979323846;
// SI units per count.
double scale(Unit unit) {
  return unit == Unit::kRotary ? 0.01 * kPi / 180.0 : 0.01e-3;
}
}  // namespace

std::uint16_t to_register(Unit unit, double si) {
  double counts = std::nearbyint(si / scale(unit));
  if (!(counts >= -32767.0)) counts = -32767.0;  // also catches NaN: saturate low, never wrap
  if (counts > 32767.0) counts = 32767.0;
  return static_cast<std::uint16_t>(static_cast<std::int16_t>(counts));
}

double from_register(Unit unit, std::uint16_t reg) {
  return static_cast<double>(static_cast<std::int16_t>(reg)) * scale(unit);
}

Placement place(int address) {
  if (address < 1 || address > 247 * kChannelsPerBoard) {
    throw std::invalid_argument("Modbus actuator address " + std::to_string(address) +
                                " is outside 1..1976 (8 channels on each of units 1..247)");
  }
  return {(address - 1) / kChannelsPerBoard + 1, (address - 1) % kChannelsPerBoard};
}

std::map<int, int> board_channels(std::span<const int> addresses) {
  std::map<int, int> channels;
  for (int a : addresses) {
    const Placement p = place(a);
    channels[p.unit] = std::max(channels[p.unit], p.channel + 1);
  }
  return channels;
}

}  // namespace facectl::modbus_map
