#include "control/face/reduced_face_model.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <string>

namespace facectl::face {

namespace {

// The jaw variables in the fit's units, and the factor each unit carries.
constexpr std::array<double, 3> kJawScale = {kPitchScale, kYawScale, kProtrusionScale};

}  // namespace

void fill_features(std::span<const double> v, const std::vector<std::array<int, 3>>& features,
                   Eigen::Ref<Eigen::VectorXd> f) {
  for (std::size_t k = 0; k < features.size(); ++k) {
    const auto [a, b, c] = features[k];
    f[static_cast<Eigen::Index>(k)] =
        (v[static_cast<std::size_t>(a)] * v[static_cast<std::size_t>(b)]) *
        v[static_cast<std::size_t>(c)];
  }
}

std::array<int, 3> feature_factors(const ReducedFaceModel& m, int column) {
  if (column < 0 || column >= static_cast<int>(m.features.size()))
    throw std::out_of_range("reduced face model: no feature column " + std::to_string(column));
  return m.features[static_cast<std::size_t>(column)];
}

void fill_feature_variables(const ReducedInput& in, std::span<double> v) {
  const std::size_t n = in.contractions.size();
  assert(v.size() >= static_cast<std::size_t>(variable_count(n)));
  std::copy(in.contractions.begin(), in.contractions.end(), v.begin());
  v[n] = in.pitch_rad * kPitchScale;
  v[n + 1] = in.yaw_rad * kYawScale;
  v[n + 2] = in.protrusion_m * kProtrusionScale;
  v[n + 3] = in.eyelid_closure[0];
  v[n + 4] = in.eyelid_closure[1];
  v[n + 5] = 1.0;
  for (std::size_t i = 0; i < n; ++i)
    v[static_cast<std::size_t>(square_variable(n, static_cast<int>(i)))] =
        in.contractions[i] * in.contractions[i];
}

// The symbolic twin of fill_features over SI jaw variables (the drift guard in
// tests/control/analysis/feature_monomials_test.cpp evaluates both on random inputs).
std::vector<Monomial> feature_monomials(const ReducedFaceModel& m) {
  const int n = static_cast<int>(m.muscles.size()), one = constant_variable(m.muscles.size());
  std::vector<Monomial> out;
  out.reserve(m.features.size());
  for (const auto& triple : m.features) {
    Monomial mono;
    for (int factor : triple) {
      if (factor < 0 || factor >= variable_count(m.muscles.size()))
        throw std::out_of_range("reduced face model: feature factor " + std::to_string(factor) +
                                " is not a variable (0.." +
                                std::to_string(variable_count(m.muscles.size()) - 1) + ")");
      if (factor == one) continue;
      if (factor >= n && factor < n + 3)
        mono.coefficient *= kJawScale[static_cast<std::size_t>(factor - n)];
      // A square variable is its muscle to the power 2.
      const int first_square = square_variable(m.muscles.size(), 0);
      const int var = factor >= first_square ? factor - first_square : factor;
      const int power = factor >= first_square ? 2 : 1;
      const auto at = std::find_if(mono.powers.begin(), mono.powers.end(),
                                   [&](const auto& p) { return p[0] == var; });
      if (at != mono.powers.end())
        (*at)[1] += power;
      else
        mono.powers.push_back({var, power});
    }
    std::sort(mono.powers.begin(), mono.powers.end());
    out.push_back(std::move(mono));
  }
  return out;
}

double evaluate_monomial(const Monomial& m, std::span<const double> variables) {
  double v = m.coefficient;
  for (const auto& [var, power] : m.powers)
    for (int e = 0; e < power; ++e) v *= variables[static_cast<std::size_t>(var)];
  return v;
}

ReducedFaceWorkspace make_reduced_workspace(const ReducedFaceModel& m) {
  return {Eigen::VectorXd::Zero(variable_count(m.muscles.size())),
          Eigen::VectorXd::Zero(m.feature_count())};
}

void evaluate_features(const ReducedFaceModel& m, ReducedFaceWorkspace& w, const ReducedInput& in) {
  std::span<double> v(w.variables.data(), static_cast<std::size_t>(w.variables.size()));
  fill_feature_variables(in, v);
  fill_features(v, m.features, w.features);
}

void evaluate(const ReducedFaceModel& m, ReducedFaceWorkspace& w, const ReducedInput& in,
              std::span<double> out) {
  evaluate_features(m, w, in);
  Eigen::Map<Eigen::VectorXd> o(out.data(), static_cast<Eigen::Index>(out.size()));
  o.noalias() = m.coefficients * w.features;
}

}  // namespace facectl::face
