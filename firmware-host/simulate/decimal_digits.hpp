#pragma once

#include <array>
#include <cstdint>
#include <cstring>

namespace facectl {

// "00", "01", ..., "99": two digits per lookup, so that six digits take two
// divisions by constants instead of six (the number writers of telemetry.csv).
inline constexpr std::array<char, 200> kDigitPairs = [] {
  std::array<char, 200> pairs{};
  for (int i = 0; i < 100; ++i) {
    pairs[2 * i] = static_cast<char>('0' + i / 10);
    pairs[2 * i + 1] = static_cast<char>('0' + i % 10);
  }
  return pairs;
}();

// Writes n < 1000000 as exactly six digits, leading zeros included.
inline void write_six_digits(char* out, std::uint32_t n) {
  const std::uint32_t high = n / 10000u, rest = n % 10000u;
  std::memcpy(out, &kDigitPairs[2 * high], 2);
  std::memcpy(out + 2, &kDigitPairs[2 * (rest / 100u)], 2);
  std::memcpy(out + 4, &kDigitPairs[2 * (rest % 100u)], 2);
}

}  // namespace facectl
