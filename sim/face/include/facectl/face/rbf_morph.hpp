// Radial-basis-function morph of thesis §3.4 (eqs. 3.27–3.35): Hardy multiquadrics
// √(d² + r_i²) with r_i = min_{j≠i} |P_i − P_j| (erratum 3), plus a linear term, under
// the linear-precision conditions, solved by LU. Exact at the landmarks and exact for
// any affine map. Used to carry a muscle map authored on one head onto another.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "facectl/face/points.hpp"

namespace facectl::face {

struct RbfMorph {
  Eigen::MatrixX3d centers;            // n × 3 source landmarks
  Eigen::VectorXd radius;              // n
  Eigen::MatrixX3d weights;            // n × 3 multiquadric coefficients h_i
  Eigen::Matrix<double, 4, 3> linear;  // rows: x, y, z, 1

  Vec3 apply(const Vec3& p) const;
};

// Throws std::invalid_argument for fewer than 4 landmarks, mismatched sizes or a
// singular system (e.g. coplanar landmarks, for which the affine part is undetermined).
RbfMorph fit_rbf(const std::vector<Vec3>& source, const std::vector<Vec3>& target);

// The same interpolation as a linear map of the values at `centers`: row q weighs them into
// the value at queries[q] (queries × centers). Linear in the values, so one matrix serves
// any displacement of the centres; each row reproduces affine functions, so sums to 1.
// Throws as fit_rbf.
Eigen::MatrixXd rbf_interpolation_matrix(const std::vector<Vec3>& centers,
                                         const std::vector<Vec3>& queries);

}  // namespace facectl::face
