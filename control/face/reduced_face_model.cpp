#include "control/face/reduced_face_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace facectl::face {

int reduced_feature_count(std::size_t muscles, std::size_t pairs) {
  return static_cast<int>(kFeaturesPerMuscle * muscles + 9 + pairs);
}

namespace {

// The jaw variables in the fit's units, for fill_features and fill_feature_variables.
std::array<double, 3> scaled_jaw(double pitch, double yaw, double prot) {
  return {pitch * kPitchScale, yaw * kYawScale, prot * kProtrusionScale};
}

}  // namespace

void fill_features(std::span<const double> c, double pitch, double yaw, double prot,
                   const std::vector<std::array<int, 2>>& pairs, Eigen::Ref<Eigen::VectorXd> f) {
  const std::size_t n = c.size();
  const auto [p, y, t] = scaled_jaw(pitch, yaw, prot);
  for (std::size_t i = 0; i < n; ++i) {
    f[i] = c[i];
    f[n + i] = c[i] * c[i];
    f[2 * n + i] = c[i] * c[i] * c[i];
    f[3 * n + i] = c[i] * p;
    f[4 * n + i] = c[i] * y;
    f[5 * n + i] = c[i] * t;
  }
  const std::size_t j = kFeaturesPerMuscle * n;
  f[j + 0] = p;
  f[j + 1] = y;
  f[j + 2] = t;
  f[j + 3] = p * p;
  f[j + 4] = y * y;
  f[j + 5] = t * t;
  f[j + 6] = p * y;
  f[j + 7] = p * t;
  f[j + 8] = y * t;
  for (std::size_t k = 0; k < pairs.size(); ++k) f[j + 9 + k] = c[pairs[k][0]] * c[pairs[k][1]];
}

// Column for column as fill_features, whose products these are in the same order.
std::array<int, 3> feature_factors(const ReducedFaceModel& m, int column) {
  const int n = static_cast<int>(m.muscles.size());
  const int pitch = n, yaw = n + 1, prot = n + 2, one = n + 3;
  const int per_muscle = static_cast<int>(kFeaturesPerMuscle) * n;
  if (column < 0 || column >= reduced_feature_count(m.muscles.size(), m.pairs.size()))
    throw std::out_of_range("reduced face model: no feature column " + std::to_string(column));
  if (column < per_muscle) {
    const int i = column % n;
    const std::array<std::array<int, 3>, kFeaturesPerMuscle> kinds = {
        {{i, one, one}, {i, i, one}, {i, i, i}, {i, pitch, one}, {i, yaw, one}, {i, prot, one}}};
    return kinds[static_cast<std::size_t>(column / n)];
  }
  const int j = column - per_muscle;
  if (j < 9) {
    const std::array<std::array<int, 3>, 9> jaw = {{{pitch, one, one},
                                                    {yaw, one, one},
                                                    {prot, one, one},
                                                    {pitch, pitch, one},
                                                    {yaw, yaw, one},
                                                    {prot, prot, one},
                                                    {pitch, yaw, one},
                                                    {pitch, prot, one},
                                                    {yaw, prot, one}}};
    return jaw[static_cast<std::size_t>(j)];
  }
  const auto [a, b] = m.pairs[static_cast<std::size_t>(j - 9)];
  return {a, b, one};
}

void fill_feature_variables(std::span<const double> c, double pitch, double yaw, double prot,
                            std::span<double> v) {
  const std::size_t n = c.size();
  std::copy(c.begin(), c.end(), v.begin());
  const std::array<double, 3> jaw = scaled_jaw(pitch, yaw, prot);
  std::copy(jaw.begin(), jaw.end(), v.begin() + static_cast<std::ptrdiff_t>(n));
  v[n + 3] = 1.0;
}

// The symbolic twin of fill_features, column for column: keep the two in step (the
// drift guard in tests/control/analysis/feature_monomials_test.cpp evaluates both on random inputs;
// feature_factors above is the other twin, tests/control/face/feature_subset_test.cpp).
std::vector<Monomial> feature_monomials(const ReducedFaceModel& m) {
  const int n = static_cast<int>(m.muscles.size());
  const int pitch = n, yaw = n + 1, prot = n + 2;
  std::vector<Monomial> f(
      static_cast<std::size_t>(reduced_feature_count(m.muscles.size(), m.pairs.size())));
  auto set = [&](std::size_t column, double scale, std::vector<std::array<int, 2>> powers) {
    f[column] = {scale, std::move(powers)};
  };
  for (int i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i), N = static_cast<std::size_t>(n);
    set(k, 1, {{i, 1}});
    set(N + k, 1, {{i, 2}});
    set(2 * N + k, 1, {{i, 3}});
    set(3 * N + k, kPitchScale, {{i, 1}, {pitch, 1}});
    set(4 * N + k, kYawScale, {{i, 1}, {yaw, 1}});
    set(5 * N + k, kProtrusionScale, {{i, 1}, {prot, 1}});
  }
  const std::size_t j = kFeaturesPerMuscle * m.muscles.size();
  set(j + 0, kPitchScale, {{pitch, 1}});
  set(j + 1, kYawScale, {{yaw, 1}});
  set(j + 2, kProtrusionScale, {{prot, 1}});
  set(j + 3, kPitchScale * kPitchScale, {{pitch, 2}});
  set(j + 4, kYawScale * kYawScale, {{yaw, 2}});
  set(j + 5, kProtrusionScale * kProtrusionScale, {{prot, 2}});
  set(j + 6, kPitchScale * kYawScale, {{pitch, 1}, {yaw, 1}});
  set(j + 7, kPitchScale * kProtrusionScale, {{pitch, 1}, {prot, 1}});
  set(j + 8, kYawScale * kProtrusionScale, {{yaw, 1}, {prot, 1}});
  for (std::size_t k = 0; k < m.pairs.size(); ++k) {
    const auto [a, b] = m.pairs[k];
    if (a == b)
      set(j + 9 + k, 1, {{a, 2}});
    else
      set(j + 9 + k, 1, {{std::min(a, b), 1}, {std::max(a, b), 1}});
  }
  return f;
}

double evaluate_monomial(const Monomial& m, std::span<const double> variables) {
  double v = m.coefficient;
  for (const auto& [var, power] : m.powers)
    for (int e = 0; e < power; ++e) v *= variables[static_cast<std::size_t>(var)];
  return v;
}

ReducedFaceWorkspace make_reduced_workspace(const ReducedFaceModel& m) {
  return {Eigen::VectorXd::Zero(m.feature_count())};
}

void evaluate_features(const ReducedFaceModel& m, ReducedFaceWorkspace& w,
                       std::span<const double> contractions, double pitch_rad, double yaw_rad,
                       double protrusion_m) {
  fill_features(contractions, pitch_rad, yaw_rad, protrusion_m, m.pairs, w.features);
}

void evaluate(const ReducedFaceModel& m, ReducedFaceWorkspace& w,
              std::span<const double> contractions, double pitch_rad, double yaw_rad,
              double protrusion_m, std::span<double> out) {
  evaluate_features(m, w, contractions, pitch_rad, yaw_rad, protrusion_m);
  Eigen::Map<Eigen::VectorXd> o(out.data(), static_cast<Eigen::Index>(out.size()));
  o.noalias() = m.coefficients * w.features;
}

}  // namespace facectl::face
