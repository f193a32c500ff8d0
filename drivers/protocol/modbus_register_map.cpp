#include "drivers/protocol/modbus_register_map.hpp"

#include <algorithm>
#include <stdexcept>

namespace facectl::modbus_map {

WireEncoding channel_encoding(Unit unit, const ActuatorEncoding& encoding) {
  if (encoding.raw == ActuatorEncoding::Raw::kInt32) {
    throw std::invalid_argument(
        "Modbus actuator board: raw int32 does not fit its one register per channel");
  }
  return WireEncoding(unit == Unit::kRotary ? ActuatorKind::kRotary : ActuatorKind::kLinear,
                      encoding);
}

std::uint16_t to_register(Unit unit, double si) {
  return channel_encoding(unit, {}).encode_u16(si);
}

double from_register(Unit unit, std::uint16_t reg) {
  return channel_encoding(unit, {}).decode_u16(reg);
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
