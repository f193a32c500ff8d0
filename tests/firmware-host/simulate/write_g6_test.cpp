// write_g6 writes the same bytes as std::to_chars(general, 6) (printf's %.6g),
// which telemetry.csv documents: on random magnitudes across and beyond its
// fast range, and on the values where a fast path would go wrong (rounding
// ties and their neighbours, powers of ten and their neighbours, zeros), never
// writing past the 16 bytes it may use.
#include "firmware-host/simulate/write_g6.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "same_text.hpp"

namespace facectl {
namespace {

// write_g6's text against to_chars', never using more than 16 bytes.
class SameAsToChars {
 public:
  void check(double v) {
    char a[64], b[64];
    std::fill(std::begin(a), std::end(a), '#');
    const std::string fast(a, write_g6(a, a + 16, v));  // 16: the room it may use
    if (std::any_of(a + 16, std::end(a), [](char c) { return c != '#'; }) && ++beyond_ <= 5)
      ADD_FAILURE() << v << ": written beyond first + 16";
    same_.compare(
        v, fast,
        std::string(b, std::to_chars(b, b + sizeof b, v, std::chars_format::general, 6).ptr));
  }
  long checked() const { return same_.checked(); }

 private:
  testing::SameText same_;
  long beyond_ = 0;
};

TEST(WriteG6, RandomMagnitudesMatchToChars) {
  SameAsToChars s;
  std::mt19937_64 rng(1);
  testing::for_random_magnitudes(rng, -11.0, 8.0, 1000000, 2, [&](double v) { s.check(v); });
  EXPECT_EQ(s.checked(), 1000000);
}

TEST(WriteG6, TiesPowersOfTenAndTheirNeighboursMatchToChars) {
  SameAsToChars s;
  const auto around = [&](double v) {
    s.check(v);
    s.check(-v);
    double below = v, above = v;
    for (int i = 0; i < 3; ++i) {
      below = std::nextafter(below, 0.0);
      above = std::nextafter(above, 1e300);
      s.check(below);
      s.check(above);
    }
  };
  for (int k = -3; k <= 15; ++k) {
    const double scale = std::pow(10.0, -k);
    for (long m = 99990; m <= 100010; ++m) {
      around((static_cast<double>(m) + 0.5) * scale);  // ties at the digit-count boundary
      around(static_cast<double>(m) * scale);
    }
    for (long m = 999990; m <= 999999; ++m) around((static_cast<double>(m) + 0.5) * scale);
  }
  std::mt19937_64 rng(2);
  std::uniform_int_distribution<long> six_digits(100000, 999999);
  for (int i = 0; i < 200000; ++i) {
    const int k = static_cast<int>(rng() % 16);
    around((static_cast<double>(six_digits(rng)) + 0.5) / std::pow(10.0, k));
  }
  // Either side of the fast path's tie margin (1e-6 of the last digit), so
  // that both the fast and the fallback rounding are exercised there.
  for (int i = 0; i < 100000; ++i) {
    const int k = static_cast<int>(rng() % 16);
    const double m = static_cast<double>(six_digits(rng));
    for (const double d : {-2e-6, -1.000001e-6, -0.999999e-6, 0.999999e-6, 1.000001e-6, 2e-6}) {
      around((m + 0.5 + d) / std::pow(10.0, k));
    }
  }
  for (int k = -11; k <= 8; ++k) around(std::pow(10.0, k));
  for (const double v :
       {0.0, -0.0, 1e-9, 9.999995e-10, 9.9999949e-10, 999999.5, 9.999995, 0.000099999949,
        0.000099999951, 1e300, std::numeric_limits<double>::infinity(), std::nan("")}) {
    s.check(v);
  }
  EXPECT_GT(s.checked(), 1000000);
}

}  // namespace
}  // namespace facectl
