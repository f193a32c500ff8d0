#include "control/face/feature_subset.hpp"

#include <algorithm>

namespace facectl::face {

FeatureSubset select_features(const ReducedFaceModel& m, std::vector<int> columns) {
  std::sort(columns.begin(), columns.end());
  columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
  FeatureSubset s;
  for (int c : columns) s.factors.push_back(feature_factors(m, c));
  s.columns = std::move(columns);
  s.variables = static_cast<std::size_t>(variable_count(m.muscles.size()));
  return s;
}

FeatureSubsetWorkspace make_subset_workspace(const FeatureSubset& s) {
  return {Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.variables)),
          Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.columns.size()))};
}

void evaluate_features(const FeatureSubset& s, FeatureSubsetWorkspace& w, const ReducedInput& in) {
  fill_feature_variables(in, std::span<double>(w.variables.data(), s.variables));
  fill_features(std::span<const double>(w.variables.data(), s.variables), s.factors, w.values);
}

}  // namespace facectl::face
