// A closed real interval [lo, hi] with the few operations the verify bounds need. Plain
// double arithmetic with round-to-nearest: the enclosures are exact up to rounding, and
// callers that need a proven bound widen the result by a rounding slack
// (docs/VERIFY.md, "Floating-point slack").
#pragma once

#include <algorithm>
#include <cmath>

namespace facectl::verify {

struct Interval {
  double lo = 0.0, hi = 0.0;

  double width() const { return hi - lo; }
  double mid() const { return 0.5 * (lo + hi); }
  // The largest |x| over the interval.
  double mag() const { return std::max(std::fabs(lo), std::fabs(hi)); }
  bool contains(double x) const { return lo <= x && x <= hi; }
  bool empty() const { return !(lo <= hi); }
};

inline Interval operator+(Interval a, Interval b) {
  return {a.lo + b.lo, a.hi + b.hi};
}
inline Interval operator-(Interval a, Interval b) {
  return {a.lo - b.hi, a.hi - b.lo};
}
inline Interval operator*(double s, Interval a) {
  return s >= 0 ? Interval{s * a.lo, s * a.hi} : Interval{s * a.hi, s * a.lo};
}
inline Interval operator*(Interval a, Interval b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {std::min(std::min(p[0], p[1]), std::min(p[2], p[3])),
          std::max(std::max(p[0], p[1]), std::max(p[2], p[3]))};
}

// x^e for an integer e ≥ 1: exact range (even powers of an interval across 0 start at 0).
inline Interval pow(Interval x, int e) {
  double a = 1, b = 1;
  for (int k = 0; k < e; ++k) {
    a *= x.lo;
    b *= x.hi;
  }
  if (e % 2 == 1) return {a, b};
  if (x.lo >= 0) return {a, b};
  if (x.hi <= 0) return {b, a};
  return {0.0, std::max(a, b)};
}

}  // namespace facectl::verify
