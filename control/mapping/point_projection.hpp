#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "control/face/feature_subset.hpp"
#include "control/face/reduced_face_model.hpp"
#include "control/mapping/point_term.hpp"

namespace facectl {

// The mapping's control-point sources folded into the reduced face model: one
// row of feature coefficients per actuator that reads points, the sum over its
// point terms of gain · (axis · the point's x, y, z coefficient rows). The tick
// then takes one short dot product per such actuator instead of evaluating the
// displacement of every control point the head has (the default rig reads 8 of
// its head's 19 points), over the few features those rows weigh.
struct PointProjection {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor rows;                      // actuators × all the model's features
  std::vector<std::size_t> actuator;  // the actuator of each row
  // What the tick evaluates: only the feature columns some row weighs (a
  // control point was fitted only on the muscles that move it), and `rows`
  // restricted to them.
  face::FeatureSubset features;
  RowMajor weights;  // actuators × features.columns
};

PointProjection project_point_terms(const face::ReducedFaceModel& reduced,
                                    std::span<const PointTerm> points);

}  // namespace facectl
