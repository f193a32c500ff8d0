#pragma once

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "firmware-host/simulate/decimal_digits.hpp"

namespace facectl {
namespace write_g6_detail {

// Powers of ten, all exact doubles; static, so not rebuilt on every call.
inline constexpr double kExact[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                    1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};

// value = digits · 10^-k with 0 <= k <= 9, in fixed notation; `keep` digits
// are significant (the rest are trailing zeros of the fraction, dropped).
inline char* fixed(char* p, const char* digits, int k, int keep) {
  if (k <= 5) {
    const int integer = 6 - k;
    std::memcpy(p, digits, 8);
    std::memcpy(p + integer + 1, digits + integer, 8);  // the fraction, one place on
    p[integer] = '.';
    return p + (keep > integer ? keep + 1 : integer);
  }
  const int zeros = k - 6;  // after "0."
  std::memcpy(p, "0.000000", 8);
  std::memcpy(p + 2 + zeros, digits, 8);
  return p + 2 + zeros + keep;
}

// value = digits · 10^-k with 10 <= k <= 14, as d[.ddddd]e-XX.
inline char* scientific(char* p, const char* digits, int k, int keep) {
  p[0] = digits[0];
  p[1] = '.';
  std::memcpy(p + 2, digits + 1, 8);
  p += keep > 1 ? keep + 1 : 1;
  std::memcpy(p, "e-", 2);
  std::memcpy(p + 2, &kDigitPairs[2 * (k - 5)], 2);
  return p + 4;
}

}  // namespace write_g6_detail

// Writes `v` exactly as std::to_chars(first, last, v, general, 6) and printf's
// "%.6g" do, byte for byte, several times faster for the magnitudes telemetry
// carries: in [1e-9, 1e6) the six significant digits come from one exact
// scaling by a power of ten and one rounding, which is decided exactly unless
// the scaled value is within 1e-6 of a tie (its error is below 1.2e-10);
// zero is written directly; anything else (other magnitudes, near ties, NaN,
// infinities) goes to std::to_chars. `last - first` must be at least 16: the
// fast path may write scratch bytes up to first + 16. Returns the end.
inline char* write_g6(char* first, char* last, double v) {
  constexpr int kMaxK = 15;
  const auto slow = [&] {
    return std::to_chars(first, last, v, std::chars_format::general, 6).ptr;
  };
  if (v == 0.0) {  // "0" or "-0": common in telemetry (values below 1e-9 are written as 0)
    char* p = first;
    if (std::signbit(v)) *p++ = '-';
    *p++ = '0';
    return p;
  }
  const double a = std::fabs(v);
  if (!(a >= 1e-9 && a < 1e6)) return slow();
  // a ≈ n · 10^-k with n of six digits. k = 5 - floor(log10(a)), with
  // floor(log10(a)) estimated from the binary exponent e as floor(e · log10(2))
  // (1233 / 4096): exact or one too small, which the check below corrects.
  const int e = static_cast<int>((std::bit_cast<std::uint64_t>(a) >> 52) & 0x7ff) - 1023;
  int k = 5 - ((e * 1233) >> 12);
  if (k < 0 || k > kMaxK) return slow();  // cannot happen in the range above; stay safe
  double s = a * write_g6_detail::kExact[k];
  if (s < 1e5) {
    if (k == kMaxK) return slow();
    s = a * write_g6_detail::kExact[++k];
  } else if (s >= 1e6) {
    if (k == 0) return slow();
    s = a * write_g6_detail::kExact[--k];
  }
  const auto whole = static_cast<std::uint32_t>(s);  // floor: 0 < s < 1e6
  const double fraction = s - whole;                 // exact: s < 2^53
  if (std::fabs(fraction - 0.5) < 1e-6) return slow();
  std::uint32_t n = whole + (fraction > 0.5 ? 1u : 0u);
  if (n >= 1000000u) {          // rounded up to the next power of ten
    if (k == 0) return slow();  // 1e+06: exponent notation
    n /= 10u;
    --k;
  }
  if (n < 100000u) return slow();  // cannot happen after the correction; stay exact anyway
  // The digits are copied in fixed 8-byte blocks (one move each, no loop);
  // the bytes past the returned end are scratch, hence the 16 bytes needed.
  char digits[16] = {};
  write_six_digits(digits, n);
  // Trailing zeros of the fraction are dropped; the leading digit (never 0)
  // and, in fixed notation, the integer digits stay.
  const int integer = k <= 5 ? 6 - k : 1;
  int keep = 6;
  while (keep > integer && digits[keep - 1] == '0') --keep;
  char* p = first;
  if (v < 0.0) *p++ = '-';
  // %.6g: exponent notation below 1e-4 (k = 10 and more), fixed otherwise.
  return k <= 9 ? write_g6_detail::fixed(p, digits, k, keep)
                : write_g6_detail::scientific(p, digits, k, keep);
}

}  // namespace facectl
