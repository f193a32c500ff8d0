// LastValueText reuses a column's last text only for the same bits: over a
// sequence with repeats, zeros of both signs and NaN, every text is
// write_g6's for that value.
#include "firmware-host/simulate/last_value_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace facectl {
namespace {

TEST(LastValueText, EveryTextIsWriteG6s) {
  std::mt19937_64 rng(5);
  std::vector<double> values = {0.0, -0.0, -0.0, 0.0, std::nan(""), std::nan(""), 1e-9, 1e300};
  for (int i = 0; i < 100000; ++i) {
    const double v = std::ldexp(static_cast<double>(rng() % 2000) - 1000.0, -10);
    const int repeats = static_cast<int>(rng() % 4);  // held values repeat
    for (int k = 0; k <= repeats; ++k) values.push_back(v);
  }
  LastValueText last;
  long differ = 0;
  for (const double v : values) {
    char a[32], b[32];
    const std::string reused(a, last.write(a, v));
    const std::string fresh(b, write_g6(b, b + sizeof b, v));
    if (reused != fresh && ++differ <= 5) ADD_FAILURE() << v << ": " << reused << " vs " << fresh;
  }
  EXPECT_GT(values.size(), 200000u);
}

}  // namespace
}  // namespace facectl
