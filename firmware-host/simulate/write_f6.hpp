#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>

#include "firmware-host/simulate/decimal_digits.hpp"

namespace facectl {

// Writes `v` exactly as std::to_chars(first, last, v, fixed, 6) and printf's
// "%.6f" do, byte for byte (telemetry.csv's time column), several times
// faster for show times: in [0, 1e5) the value in millionths, v · 1e6, is
// below 2^37, so that one rounding leaves it within 7.6e-6 of the exact
// product, and its rounding to an integer is decided exactly unless it lies
// within 1e-4 of a tie. Anything else (negative values, -0, larger values,
// near ties, NaN, infinities) goes to std::to_chars. Returns the end.
inline char* write_f6(char* first, char* last, double v) {
  const auto slow = [&] { return std::to_chars(first, last, v, std::chars_format::fixed, 6).ptr; };
  if (!(v >= 0.0 && v < 1e5) || std::signbit(v)) return slow();
  const double s = v * 1e6;
  const auto whole = static_cast<std::uint64_t>(s);        // floor: 0 <= s < 1e11
  const double fraction = s - static_cast<double>(whole);  // exact
  if (std::fabs(fraction - 0.5) < 1e-4) return slow();
  const std::uint64_t millionths = whole + (fraction > 0.5 ? 1u : 0u);
  char* p = std::to_chars(first, last, millionths / 1000000u).ptr;
  if (last - p < 7) return slow();  // no room for the fraction: let to_chars report it
  *p++ = '.';
  write_six_digits(p, static_cast<std::uint32_t>(millionths % 1000000u));
  return p + 6;
}

}  // namespace facectl
