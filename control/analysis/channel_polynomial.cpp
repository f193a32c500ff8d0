#include "control/analysis/channel_polynomial.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace facectl::verify {

double ChannelPolynomial::evaluate(std::span<const double> variables) const {
  double v = constant;
  for (const PolynomialTerm& t : terms) v += face::evaluate_monomial(t.monomial, variables);
  return v;
}

std::vector<int> ChannelPolynomial::used_variables() const {
  std::vector<char> used(static_cast<std::size_t>(variable_count), 0);
  for (const PolynomialTerm& t : terms)
    if (t.monomial.coefficient != 0.0)
      for (const auto& f : t.monomial.powers) used[static_cast<std::size_t>(f[0])] = 1;
  std::vector<int> out;
  for (int v = 0; v < variable_count; ++v)
    if (used[static_cast<std::size_t>(v)]) out.push_back(v);
  return out;
}

ChannelPolynomial make_channel_polynomial(const face::ReducedFaceModel& model,
                                          const ChannelTerms& terms) {
  const int points = static_cast<int>(model.control_points.size());
  ChannelPolynomial p;
  p.variable_count = face::constant_variable(model.muscles.size());
  if (!std::isfinite(terms.offset))
    throw std::invalid_argument("channel polynomial: offset is not finite");
  p.constant = terms.offset;

  // Accumulate coefficient and magnitude per distinct monomial (keyed by its powers).
  std::map<std::vector<std::array<int, 2>>, std::array<double, 2>> acc;
  auto add = [&](const std::vector<std::array<int, 2>>& powers, double c) {
    auto& a = acc[powers];
    a[0] += c;
    a[1] += std::fabs(c);
  };

  const std::vector<face::Monomial> features = face::feature_monomials(model);
  for (const ControlPointTerm& t : terms.points) {
    if (t.control_point < 0 || t.control_point >= points)
      throw std::invalid_argument("channel polynomial: control point " +
                                  std::to_string(t.control_point) + " is not in 0.." +
                                  std::to_string(points - 1));
    const double norm =
        std::sqrt(t.axis[0] * t.axis[0] + t.axis[1] * t.axis[1] + t.axis[2] * t.axis[2]);
    if (!(std::fabs(norm - 1.0) <= 1e-9))
      throw std::invalid_argument("channel polynomial: the axis of control point " +
                                  model.control_points[t.control_point] +
                                  " is not a unit vector (length " + std::to_string(norm) + ")");
    if (!std::isfinite(t.gain))
      throw std::invalid_argument("channel polynomial: a control-point gain is not finite");
    for (int k = 0; k < 3; ++k) {
      const double w = t.gain * t.axis[static_cast<std::size_t>(k)];
      if (w == 0.0) continue;
      const auto row = model.coefficients.row(3 * t.control_point + k);
      for (std::size_t f = 0; f < features.size(); ++f) {
        const double c = row(static_cast<Eigen::Index>(f));
        if (c != 0.0) add(features[f].powers, w * c * features[f].coefficient);
      }
    }
  }
  for (const LinearTerm& l : terms.linear) {
    if (l.variable < 0 || l.variable >= p.variable_count)
      throw std::invalid_argument("channel polynomial: variable " + std::to_string(l.variable) +
                                  " is not in 0.." + std::to_string(p.variable_count - 1));
    if (!std::isfinite(l.gain))
      throw std::invalid_argument("channel polynomial: a linear gain is not finite");
    if (l.gain != 0.0) add({{l.variable, 1}}, l.gain);
  }
  for (const auto& [powers, a] : acc)
    if (a[1] != 0.0) p.terms.push_back({face::Monomial{a[0], powers}, a[1]});
  return p;
}

}  // namespace facectl::verify
