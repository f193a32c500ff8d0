#include "control/mapping/linkage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/mapping/calibration_curve.hpp"

namespace facectl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Linkage, LeverPullIsRadiusTimesAngle) {
  Linkage l;
  l.kind = Linkage::Kind::kLever;
  l.radius = 0.012;
  EXPECT_NEAR(*l.to_effector(30 * kDeg), 0.012 * 30 * kDeg, 1e-15);
  EXPECT_NEAR(*l.to_actuator(0.004), 0.004 / 0.012, 1e-15);
}

TEST(Linkage, SliderCrankMatchesTheClosedFormAndRoundTrips) {
  Linkage l;
  l.kind = Linkage::Kind::kSliderCrank;
  l.input = 0.02;    // crank on the jaw hinge
  l.coupler = 0.06;  // rod
  l.offset = 0.005;
  // At a crank angle of 0 the pin is at (r, 0): s = r + sqrt(l^2 - e^2).
  EXPECT_NEAR(*l.to_actuator(0.0), 0.02 + std::sqrt(0.06 * 0.06 - 0.005 * 0.005), 1e-15);
  // A jaw crank mounted at 83°, so the jaw's -4..18° keeps it near 90° to the rod.
  l.phase = 83 * kDeg;
  l.effector_min = -10 * kDeg;
  l.effector_max = 30 * kDeg;
  for (double deg = -4.0; deg <= 18.0; deg += 0.5) {
    const double s = *l.to_actuator(deg * kDeg);
    ASSERT_NEAR(*l.to_effector(s), deg * kDeg, 1e-9) << deg;
  }
}

TEST(Linkage, FourBarRoundTripsAndClosesItsLoop) {
  Linkage l;
  l.kind = Linkage::Kind::kFourBar;
  l.ground = 0.05;
  l.input = 0.015;
  l.coupler = 0.05;
  l.output = 0.02;
  for (double deg = 30.0; deg <= 150.0; deg += 2.0) {
    const auto psi = l.to_effector(deg * kDeg);
    ASSERT_TRUE(psi.has_value()) << deg;
    // Loop closure: the coupler really has its length.
    const double ax = l.input * std::cos(deg * kDeg);
    const double ay = l.input * std::sin(deg * kDeg);
    const double bx = l.ground + l.output * std::cos(*psi);
    const double by = l.output * std::sin(*psi);
    ASSERT_NEAR(std::hypot(bx - ax, by - ay), l.coupler, 1e-12) << deg;
    ASSERT_NEAR(*l.to_actuator(*psi), deg * kDeg, 1e-9) << deg;
  }
}

TEST(Linkage, UnreachablePositionsAreReportedNotInvented) {
  Linkage l;
  l.kind = Linkage::Kind::kSliderCrank;
  l.input = 0.02;
  l.coupler = 0.01;  // rod shorter than the pin's height above the line at 90°
  EXPECT_FALSE(l.to_actuator(90 * kDeg).has_value());
}

TEST(CalibrationCurve, EvaluatesInvertsAndHoldsItsEnds) {
  CalibrationCurve c;
  const double x[] = {0.0, 1.0, 3.0};
  const double y[] = {10.0, 20.0, 60.0};
  ASSERT_TRUE(c.set(x, y, 3));
  EXPECT_DOUBLE_EQ(c.evaluate(2.0), 40.0);
  EXPECT_DOUBLE_EQ(c.evaluate(-5.0), 10.0);
  EXPECT_DOUBLE_EQ(c.evaluate(9.0), 60.0);
  EXPECT_DOUBLE_EQ(*c.inverse(40.0), 2.0);
  EXPECT_FALSE(c.inverse(61.0).has_value());
}

TEST(CalibrationCurve, RefusesANonMonotoneCurveAndNamesThePoint) {
  CalibrationCurve c;
  const double x[] = {0.0, 1.0, 2.0, 3.0};
  const double y[] = {0.0, 5.0, 4.0, 9.0};
  std::size_t bad = 0;
  EXPECT_FALSE(c.set(x, y, 4, &bad));
  EXPECT_EQ(bad, 2u);
  EXPECT_TRUE(c.empty());
}

}  // namespace
}  // namespace facectl
