#pragma once

#include <array>
#include <cstdint>

namespace facectl {

// One CAN frame as the drivers see it: classic (up to 8 data bytes) or CAN FD
// (up to 64). Plain data, so encoders fill it in place without allocating.
struct CanFrame {
  std::uint32_t id = 0;  // 11-bit identifier
  std::uint8_t len = 0;
  bool fd = false;
  std::array<std::uint8_t, 64> data{};
};

inline void put_u16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v & 0xFF);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
inline void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF);
}
inline std::uint16_t get_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
inline std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

}  // namespace facectl
