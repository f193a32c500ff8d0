#include "control/mapping/point_projection.hpp"

#include <algorithm>

namespace facectl {

PointProjection project_point_terms(const face::ReducedFaceModel& reduced,
                                    std::span<const PointTerm> points) {
  PointProjection out;
  for (const PointTerm& p : points) {
    if (std::find(out.actuator.begin(), out.actuator.end(), p.actuator) == out.actuator.end())
      out.actuator.push_back(p.actuator);
  }
  out.rows.setZero(static_cast<Eigen::Index>(out.actuator.size()), reduced.feature_count());
  for (const PointTerm& p : points) {
    const auto row = static_cast<Eigen::Index>(
        std::find(out.actuator.begin(), out.actuator.end(), p.actuator) - out.actuator.begin());
    for (Eigen::Index k = 0; k < 3; ++k) {
      const auto source = static_cast<Eigen::Index>(3 * p.point) + k;
      out.rows.row(row) +=
          p.gain * p.axis[static_cast<std::size_t>(k)] * reduced.coefficients.row(source);
    }
  }
  std::vector<int> used;
  for (Eigen::Index k = 0; k < out.rows.cols(); ++k) {
    if ((out.rows.col(k).array() != 0.0).any()) used.push_back(static_cast<int>(k));
  }
  out.features = face::select_features(reduced, used);
  out.weights.resize(out.rows.rows(), static_cast<Eigen::Index>(used.size()));
  for (std::size_t k = 0; k < used.size(); ++k)
    out.weights.col(static_cast<Eigen::Index>(k)) = out.rows.col(used[k]);
  return out;
}

}  // namespace facectl
