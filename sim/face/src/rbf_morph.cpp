#include "facectl/face/rbf_morph.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace facectl::face {
namespace {

// r_i = min_{j≠i} |P_i − P_j| (erratum 3).
Eigen::VectorXd nearest_other_distance(const std::vector<Vec3>& source) {
  const Eigen::Index n = static_cast<Eigen::Index>(source.size());
  Eigen::VectorXd radius(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < n; ++j)
      if (j != i) best = std::min(best, (source[i] - source[j]).norm());
    radius[i] = best;
  }
  return radius;
}

// [Φ L; Lᵀ 0], factored, with Φ_ji = φ_i(P_j) and L_j = (x_j, y_j, z_j, 1).
Eigen::FullPivLU<Eigen::MatrixXd> rbf_system(const std::vector<Vec3>& source,
                                             const Eigen::VectorXd& radius) {
  const Eigen::Index n = static_cast<Eigen::Index>(source.size());
  if (n < 4) throw std::invalid_argument("rbf: need at least 4 landmarks");
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 4, n + 4);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i)
      A(j, i) = std::sqrt((source[j] - source[i]).squaredNorm() + radius[i] * radius[i]);
    for (int c = 0; c < 3; ++c) {
      A(j, n + c) = source[j][c];
      A(n + c, j) = source[j][c];
    }
    A(j, n + 3) = 1;
    A(n + 3, j) = 1;
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (!lu.isInvertible()) throw std::invalid_argument("rbf: singular landmark configuration");
  return lu;
}

}  // namespace

Vec3 RbfMorph::apply(const Vec3& p) const {
  Eigen::RowVector3d out = p.transpose() * linear.topRows<3>() + linear.row(3);
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    double d2 = (centers.row(i).transpose() - p).squaredNorm();
    out += std::sqrt(d2 + radius[i] * radius[i]) * weights.row(i);
  }
  return out.transpose();
}

RbfMorph fit_rbf(const std::vector<Vec3>& source, const std::vector<Vec3>& target) {
  const Eigen::Index n = static_cast<Eigen::Index>(source.size());
  if (source.size() != target.size())
    throw std::invalid_argument("rbf: source and target landmark counts differ");
  RbfMorph m;
  m.radius = nearest_other_distance(source);
  const auto lu = rbf_system(source, m.radius);
  m.centers.resize(n, 3);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n + 4, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    m.centers.row(i) = source[i].transpose();
    b.row(i) = target[i].transpose();
  }
  Eigen::MatrixXd x = lu.solve(b);
  m.weights = x.topRows(n);
  m.linear = x.bottomRows(4);
  return m;
}

Eigen::MatrixXd rbf_interpolation_matrix(const std::vector<Vec3>& centers,
                                         const std::vector<Vec3>& queries) {
  const Eigen::Index n = static_cast<Eigen::Index>(centers.size());
  const Eigen::VectorXd radius = nearest_other_distance(centers);
  // Column k: the interpolant's coefficients [h; a] for the unit value at centre k.
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(n + 4, n);
  unit.topRows(n).setIdentity();
  const Eigen::MatrixXd coefficients = rbf_system(centers, radius).solve(unit);
  Eigen::MatrixXd basis(static_cast<Eigen::Index>(queries.size()), n + 4);
  for (Eigen::Index q = 0; q < basis.rows(); ++q) {
    const Vec3& p = queries[q];
    for (Eigen::Index i = 0; i < n; ++i)
      basis(q, i) = std::sqrt((p - centers[i]).squaredNorm() + radius[i] * radius[i]);
    basis.block<1, 3>(q, n) = p.transpose();
    basis(q, n + 3) = 1;
  }
  return basis * coefficients;
}

}  // namespace facectl::face
