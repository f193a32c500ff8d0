#include "control/limits/coupled_constraints.hpp"

#include <gtest/gtest.h>

#include <random>

namespace facectl {
namespace {

CoupledConstraints::Constraint row(std::string name,
                                   std::initializer_list<std::pair<std::size_t, double>> terms,
                                   double bound) {
  CoupledConstraints::Constraint c;
  c.name = std::move(name);
  for (const auto& [i, a] : terms) {
    c.index[c.terms] = i;
    c.coeff[c.terms] = a;
    ++c.terms;
  }
  c.bound = bound;
  return c;
}

TEST(CoupledConstraints, AntagonistsAreProjectedToTheNearestAdmissiblePoint) {
  CoupledConstraints cc;
  cc.add(row("zygomaticus vs depressor", {{0, 1.0}, {1, 1.0}}, 1.0));
  const double lo[] = {0, 0};
  const double hi[] = {1, 1};
  const double ref[] = {0, 0};
  cc.finalize(2, lo, hi, ref);
  double x[] = {0.8, 0.6};
  double worst = 0;
  EXPECT_EQ(cc.project(x, &worst), 1u);
  EXPECT_NEAR(worst, 0.4, 1e-12);
  EXPECT_NEAR(x[0], 0.6, 1e-12);
  EXPECT_NEAR(x[1], 0.4, 1e-12);
  double ok[] = {0.3, 0.2};
  EXPECT_EQ(cc.project(ok), 0u);
  EXPECT_DOUBLE_EQ(ok[0], 0.3);
}

TEST(CoupledConstraints, ARejectedReferenceNamesTheConstraint) {
  CoupledConstraints cc;
  cc.add(row("lip vs jaw", {{0, 1.0}, {1, 1.0}}, 0.5));
  const double lo[] = {0, 0};
  const double hi[] = {1, 1};
  const double ref[] = {0.4, 0.4};
  try {
    cc.finalize(2, lo, hi, ref);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'lip vs jaw'"), std::string::npos);
  }
}

// Random polytopes like a face's: antagonist pairs, a jaw-opening against
// lip constraint, and a yaw band that widens with pitch. Every projected point
// satisfies every constraint and the box; variables outside violated groups
// never move.
TEST(CoupledConstraints, EveryProjectedPointIsAdmissible) {
  CoupledConstraints cc;
  // x0..x3 muscles in [0,1]; x4 pitch in [-0.07, 0.31]; x5 yaw in [-0.087, 0.087]; x6 untouched.
  cc.add(row("antagonists left", {{0, 1.0}, {1, 1.0}}, 1.0));
  cc.add(row("antagonists right", {{2, 1.0}, {3, 1.2}}, 1.0));
  cc.add(row("jaw vs lip", {{4, 2.0}, {0, 0.5}}, 0.5));
  cc.add(row("yaw band +", {{5, 1.0}, {4, -0.2}}, 0.03));
  cc.add(row("yaw band -", {{5, -1.0}, {4, -0.2}}, 0.03));
  const double lo[] = {0, 0, 0, 0, -0.07, -0.087, -1};
  const double hi[] = {1, 1, 1, 1, 0.31, 0.087, 1};
  const double ref[] = {0, 0, 0, 0, 0, 0, 0};
  cc.finalize(7, lo, hi, ref);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long fired = 0;
  for (int n = 0; n < 200000; ++n) {
    double x[7];
    for (int i = 0; i < 7; ++i) x[i] = lo[i] + (hi[i] - lo[i]) * u(rng);
    const double untouched = x[6];
    if (cc.project(x) != 0) ++fired;
    for (std::size_t c = 0; c < cc.size(); ++c) {
      ASSERT_LE(cc.constraint(c).value(x), cc.constraint(c).bound + 1e-9) << n << " " << c;
    }
    for (int i = 0; i < 7; ++i) {
      ASSERT_GE(x[i], lo[i] - 1e-12);
      ASSERT_LE(x[i], hi[i] + 1e-12);
    }
    ASSERT_EQ(x[6], untouched);
  }
  EXPECT_GT(fired, 10000);  // the test did exercise the projection
}

}  // namespace
}  // namespace facectl
