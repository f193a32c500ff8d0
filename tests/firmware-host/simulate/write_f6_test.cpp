// write_f6 writes the same bytes as std::to_chars(fixed, 6) (printf's %.6f),
// which telemetry.csv's time column documents: on every tick of an hour at
// 1 kHz, on random values across and beyond its fast range, and where a fast
// path would go wrong (ties, which are exact at odd multiples of 1/128, and
// values either side of its tie margin).
#include "firmware-host/simulate/write_f6.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "same_text.hpp"

namespace facectl {
namespace {

// write_f6's text against printf's.
class SameAsPrintf {
 public:
  void check(double v) {
    char a[400], b[400];
    std::snprintf(b, sizeof b, "%.6f", v);
    same_.compare(v, std::string(a, write_f6(a, a + sizeof a, v)), b);
  }
  long checked() const { return same_.checked(); }

 private:
  testing::SameText same_;
};

TEST(WriteF6, EveryTickOfAnHourMatchesPrintf) {
  SameAsPrintf s;
  const double period = 1.0 / 1000.0;
  for (long k = 0; k <= 3600000; ++k) s.check(static_cast<double>(k) * period);
  EXPECT_EQ(s.checked(), 3600001);
}

TEST(WriteF6, RandomValuesTiesAndSpecialsMatchPrintf) {
  SameAsPrintf s;
  std::mt19937_64 rng(3);
  testing::for_random_magnitudes(rng, -9.0, 7.0, 1000000, 8, [&](double v) { s.check(v); });
  std::uniform_int_distribution<long> millionths(0, 99999999999L);
  for (int i = 0; i < 200000; ++i) {
    const auto m = static_cast<double>(millionths(rng));
    s.check(static_cast<double>(2 * (i % 1000000) + 1) / 128.0);  // exact ties
    // Either side of the tie margin (1e-4 of a millionth).
    for (const double d : {-2e-4, -1.0001e-4, -0.9999e-4, 0.0, 0.9999e-4, 1.0001e-4, 2e-4}) {
      s.check((m + 0.5 + d) / 1e6);
    }
  }
  for (const double v : {0.0, -0.0, 99999.9999995, 1e5, 1e300, -1e300,
                         std::numeric_limits<double>::infinity(), std::nan("")}) {
    s.check(v);
  }
  EXPECT_GT(s.checked(), 2000000);
}

}  // namespace
}  // namespace facectl
