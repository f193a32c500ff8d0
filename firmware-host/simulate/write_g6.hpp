#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>

namespace facectl {

// Writes `v` exactly as std::to_chars(first, last, v, general, 6) and printf's
// "%.6g" do, byte for byte, several times faster for the magnitudes telemetry
// carries: in [1e-4, 1e6) the six significant digits come from one exact
// scaling by a power of ten and one rounding, which is decided exactly unless
// the scaled value is within 1e-6 of a tie (its error is below 1.2e-10);
// anything else (other magnitudes, near ties, zero, NaN, infinities) goes to
// std::to_chars. `last - first` must be at least 16. Returns the end.
inline char* write_g6(char* first, char* last, double v) {
  constexpr double kExact[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};  // exact doubles
  const auto slow = [&] {
    return std::to_chars(first, last, v, std::chars_format::general, 6).ptr;
  };
  const double a = std::fabs(v);
  if (!(a >= 1e-4 && a < 1e6)) return slow();
  // a ≈ n · 10^-k with n of six digits; k from the magnitude, then corrected.
  int k = a >= 1e5    ? 0
          : a >= 1e4  ? 1
          : a >= 1e3  ? 2
          : a >= 1e2  ? 3
          : a >= 1e1  ? 4
          : a >= 1.0  ? 5
          : a >= 1e-1 ? 6
          : a >= 1e-2 ? 7
          : a >= 1e-3 ? 8
                      : 9;
  double s = a * kExact[k];
  if (s < 1e5) {
    if (k == 9) return slow();
    s = a * kExact[++k];
  } else if (s >= 1e6) {
    if (k == 0) return slow();
    s = a * kExact[--k];
  }
  const double whole = std::floor(s);
  const double fraction = s - whole;  // exact: s < 2^53
  if (std::fabs(fraction - 0.5) < 1e-6) return slow();
  auto n = static_cast<std::uint32_t>(whole) + (fraction > 0.5 ? 1u : 0u);
  if (n >= 1000000u) {          // rounded up to the next power of ten
    if (k == 0) return slow();  // 1e+06: exponent notation
    n /= 10u;
    --k;
  }
  if (n < 100000u) return slow();  // cannot happen after the correction; stay exact anyway
  char digits[6];
  for (int i = 5; i >= 0; --i, n /= 10u) digits[i] = static_cast<char>('0' + n % 10u);
  char* p = first;
  if (v < 0.0) *p++ = '-';
  // Fixed notation: value = digits · 10^-k, trailing fraction zeros dropped.
  int keep = 6;
  while (keep > 6 - k && keep > 0 && digits[keep - 1] == '0') --keep;
  if (k <= 5) {
    const int integer = 6 - k;
    for (int i = 0; i < integer; ++i) *p++ = digits[i];
    if (keep > integer) {
      *p++ = '.';
      for (int i = integer; i < keep; ++i) *p++ = digits[i];
    }
  } else {
    *p++ = '0';
    *p++ = '.';
    for (int i = 0; i < k - 6; ++i) *p++ = '0';
    for (int i = 0; i < keep; ++i) *p++ = digits[i];
  }
  return p;
}

}  // namespace facectl
