// LinearMapping sums only its non-zero gains; it must agree with the dense
// product it replaces, including after a gain is overwritten or zeroed.
#include "control/mapping/linear_mapping.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace facectl {
namespace {

TEST(LinearMapping, EqualsTheDenseProductAfterGainsAreSetOverwrittenAndZeroed) {
  constexpr std::size_t kActuators = 7, kSignals = 11;
  LinearMapping m(kActuators, kSignals);
  std::vector<double> dense(kActuators * kSignals, 0.0), offset(kActuators, 0.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::uniform_int_distribution<std::size_t> pick_a(0, kActuators - 1), pick_s(0, kSignals - 1);
  for (std::size_t a = 0; a < kActuators; ++a) m.set_offset(a, offset[a] = u(rng));
  for (int k = 0; k < 40; ++k) {
    const std::size_t a = pick_a(rng), s = pick_s(rng);
    const double g = k % 5 == 4 ? 0.0 : u(rng);  // some gains are zeroed again
    m.set_gain(a, s, g);
    dense[a * kSignals + s] = g;
  }
  std::array<double, kMaxFaceSignals> x{};
  std::array<double, kMaxActuators> y{};
  for (int trial = 0; trial < 20; ++trial) {
    for (std::size_t s = 0; s < kSignals; ++s) x[s] = u(rng);
    m.apply(x, y);
    for (std::size_t a = 0; a < kActuators; ++a) {
      double expected = offset[a];
      for (std::size_t s = 0; s < kSignals; ++s) expected += dense[a * kSignals + s] * x[s];
      EXPECT_NEAR(y[a], expected, 1e-12) << "actuator " << a;
      bool driven = false;
      for (std::size_t s = 0; s < kSignals; ++s) driven = driven || dense[a * kSignals + s] != 0;
      EXPECT_EQ(m.drives(a), driven) << "actuator " << a;
    }
  }
}

}  // namespace
}  // namespace facectl
