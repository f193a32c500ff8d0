#include "facectl/face/rbf_morph.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace facectl::face {

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
  if (n < 4) throw std::invalid_argument("rbf: need at least 4 landmarks");
  RbfMorph m;
  m.centers.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) m.centers.row(i) = source[i].transpose();
  m.radius.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < n; ++j)
      if (j != i) best = std::min(best, (source[i] - source[j]).norm());
    m.radius[i] = best;
  }
  // [Φ L; Lᵀ 0][h; a] = [Q; 0] with Φ_ji = φ_i(P_j) and L_j = (x_j, y_j, z_j, 1).
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 4, n + 4);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n + 4, 3);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i)
      A(j, i) = std::sqrt((source[j] - source[i]).squaredNorm() + m.radius[i] * m.radius[i]);
    for (int c = 0; c < 3; ++c) {
      A(j, n + c) = source[j][c];
      A(n + c, j) = source[j][c];
    }
    A(j, n + 3) = 1;
    A(n + 3, j) = 1;
    b.row(j) = target[j].transpose();
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (!lu.isInvertible()) throw std::invalid_argument("rbf: singular landmark configuration");
  Eigen::MatrixXd x = lu.solve(b);
  m.weights = x.topRows(n);
  m.linear = x.bottomRows(4);
  return m;
}

}  // namespace facectl::face
