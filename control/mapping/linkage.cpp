#include "control/mapping/linkage.hpp"

#include <cmath>
#include <numbers>

namespace facectl {
namespace {

struct Point {
  double x;
  double y;
};

// The intersections of circle (c0, r0) and circle (c1, r1); `side` (+1/-1)
// picks the one left or right of the line c0 -> c1.
std::optional<Point> circle_intersection(Point c0, double r0, Point c1, double r1, int side) {
  const double dx = c1.x - c0.x;
  const double dy = c1.y - c0.y;
  const double d = std::hypot(dx, dy);
  if (d <= 0.0 || d > r0 + r1 || d < std::fabs(r0 - r1)) return std::nullopt;
  const double a = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d);
  const double h = std::sqrt(std::fmax(0.0, r0 * r0 - a * a));
  const Point m{c0.x + a * dx / d, c0.y + a * dy / d};
  const double s = side >= 0 ? 1.0 : -1.0;
  return Point{m.x - s * h * dy / d, m.y + s * h * dx / d};
}

std::optional<double> four_bar_output(const Linkage& l, double theta) {
  const Point a{l.input * std::cos(theta), l.input * std::sin(theta)};
  const auto b = circle_intersection(a, l.coupler, {l.ground, 0.0}, l.output, l.branch);
  if (!b) return std::nullopt;
  return std::atan2(b->y, b->x - l.ground);
}

std::optional<double> four_bar_input(const Linkage& l, double psi) {
  const Point b{l.ground + l.output * std::cos(psi), l.output * std::sin(psi)};
  // Of the two crank positions that close the loop, the one on this branch
  // is the one whose forward solution gives psi back.
  for (int side : {1, -1}) {
    const auto a = circle_intersection({0.0, 0.0}, l.input, b, l.coupler, side);
    if (!a) continue;
    const double theta = std::atan2(a->y, a->x);
    const auto back = four_bar_output(l, theta);
    if (back && std::fabs(std::remainder(*back - psi, 2.0 * std::numbers::pi)) < 1e-9) return theta;
  }
  return std::nullopt;
}

}  // namespace

std::string_view to_string(Linkage::Kind kind) {
  switch (kind) {
    case Linkage::Kind::kNone:
      return "none";
    case Linkage::Kind::kLever:
      return "lever";
    case Linkage::Kind::kFourBar:
      return "four_bar";
    case Linkage::Kind::kSliderCrank:
      return "slider_crank";
  }
  return "?";
}

std::optional<double> Linkage::to_actuator(double effector) const {
  switch (kind) {
    case Kind::kNone:
      return effector;
    case Kind::kLever:
      return effector / radius;
    case Kind::kFourBar:
      return four_bar_input(*this, effector + phase);
    case Kind::kSliderCrank: {
      const double theta = effector + phase;
      const double y = input * std::sin(theta) - offset;
      const double under = coupler * coupler - y * y;
      if (under < 0.0) return std::nullopt;
      return input * std::cos(theta) + std::sqrt(under);
    }
  }
  return std::nullopt;
}

std::optional<double> Linkage::to_effector(double actuator) const {
  switch (kind) {
    case Kind::kNone:
      return actuator;
    case Kind::kLever:
      return actuator * radius;
    case Kind::kFourBar: {
      const auto psi = four_bar_output(*this, actuator);
      if (!psi) return std::nullopt;
      return std::remainder(*psi - phase, 2.0 * std::numbers::pi);
    }
    case Kind::kSliderCrank: {
      // Crank pin on the circle of radius `input` at distance `coupler` from
      // the slider pin (s, offset); the branch with the pin above the line
      // through the pivot and the slider is the one to_actuator describes.
      std::optional<double> best;
      double best_miss = 0.0;
      for (int side : {1, -1}) {
        const auto p = circle_intersection({0.0, 0.0}, input, {actuator, offset}, coupler, side);
        if (!p) continue;
        const double theta = std::remainder(std::atan2(p->y, p->x) - phase, 2.0 * std::numbers::pi);
        const auto back = to_actuator(theta);
        if (!back || std::fabs(*back - actuator) > 1e-9) continue;
        // Distance outside the working range (0 inside it).
        const double miss = std::fmax(0.0, std::fmax(effector_min - theta, theta - effector_max));
        if (!best || miss < best_miss) {
          best = theta;
          best_miss = miss;
        }
      }
      return best;
    }
  }
  return std::nullopt;
}

}  // namespace facectl
