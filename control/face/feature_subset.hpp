// Some columns of the reduced face model's features, worked out without the rest. A
// caller that needs only a few combinations of the outputs uses only the columns they
// weigh, since each control point was fitted only on the muscles that move it (the
// default rig's eight point-following servos weigh a fraction of the head's features).
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "control/face/reduced_face_model.hpp"

namespace facectl::face {

struct FeatureSubset {
  std::vector<int> columns;                 // feature columns of the model, ascending
  std::vector<std::array<int, 3>> factors;  // per column, as feature_factors()
  std::size_t variables = 0;                // variable_count(n), as fill_feature_variables()
};

// Throws std::out_of_range for a column the model does not have.
FeatureSubset select_features(const ReducedFaceModel& m, std::vector<int> columns);

struct FeatureSubsetWorkspace {
  Eigen::VectorXd variables;
  Eigen::VectorXd values;  // one per column of the subset, in its order
};

FeatureSubsetWorkspace make_subset_workspace(const FeatureSubset& s);

// Fills w.values; each equals its column of evaluate_features() bit for bit.
void evaluate_features(const FeatureSubset& s, FeatureSubsetWorkspace& w, const ReducedInput& in);

}  // namespace facectl::face
