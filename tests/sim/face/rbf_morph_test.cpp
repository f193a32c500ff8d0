// RBF morph of thesis §3.4: exact at the landmarks, and exact for any affine map thanks
// to the linear term and the conditions of eqs. 3.32–3.35.
#include "facectl/face/rbf_morph.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace facectl::face {
namespace {

std::vector<Vec3> random_cloud(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.08, 0.08);
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i) v.push_back(Vec3(u(rng), u(rng), u(rng)));
  return v;
}

TEST(RbfMorph, ExactAtTheLandmarks) {
  std::mt19937 rng(11);
  std::vector<Vec3> src = random_cloud(47, rng), dst = random_cloud(47, rng);
  RbfMorph g = fit_rbf(src, dst);
  for (std::size_t i = 0; i < src.size(); ++i) EXPECT_LT((g.apply(src[i]) - dst[i]).norm(), 1e-10);
}

TEST(RbfMorph, ReproducesAnAffineMapEverywhere) {
  std::mt19937 rng(12);
  std::vector<Vec3> src = random_cloud(31, rng);
  Mat3 A;
  A << 1.1, 0.2, -0.1, 0.05, 0.9, 0.3, -0.2, 0.1, 1.3;
  const Vec3 t(0.01, -0.02, 0.005);
  std::vector<Vec3> dst;
  for (const Vec3& s : src) dst.push_back(A * s + t);
  RbfMorph g = fit_rbf(src, dst);
  EXPECT_LT(g.weights.cwiseAbs().maxCoeff(), 1e-8);  // no radial part is needed
  for (const Vec3& p : random_cloud(200, rng)) EXPECT_LT((g.apply(p) - (A * p + t)).norm(), 1e-10);
}

TEST(RbfMorph, RadiusIsDistanceToNearestOtherLandmark) {
  std::vector<Vec3> src = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3),
                           Vec3(1, 1, 1)};
  RbfMorph g = fit_rbf(src, src);
  EXPECT_DOUBLE_EQ(g.radius[0], 1.0);
  EXPECT_DOUBLE_EQ(g.radius[3], std::sqrt(1 + 1 + 4.0));
}

// The matrix form (facectl serve's skin weights) is the same interpolant, any values.
TEST(RbfMorph, InterpolationMatrixIsTheMorphAsALinearMap) {
  std::mt19937 rng(13);
  const std::vector<Vec3> src = random_cloud(23, rng), dst = random_cloud(23, rng);
  const std::vector<Vec3> queries = random_cloud(50, rng);
  const Eigen::MatrixXd W = rbf_interpolation_matrix(src, queries);
  const RbfMorph g = fit_rbf(src, dst);
  Eigen::MatrixX3d values(23, 3);
  for (int i = 0; i < 23; ++i) values.row(i) = dst[i].transpose();
  for (std::size_t q = 0; q < queries.size(); ++q) {
    const Vec3 got = (W.row(static_cast<Eigen::Index>(q)) * values).transpose();
    EXPECT_LT((got - g.apply(queries[q])).norm(), 1e-10);
    EXPECT_NEAR(W.row(static_cast<Eigen::Index>(q)).sum(), 1.0, 1e-10);
  }
  const Eigen::MatrixXd at_centers = rbf_interpolation_matrix(src, src);
  EXPECT_LT((at_centers - Eigen::MatrixXd::Identity(23, 23)).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(RbfMorph, RejectsTooFewOrMismatchedLandmarks) {
  std::vector<Vec3> three = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THROW(fit_rbf(three, three), std::invalid_argument);
  std::vector<Vec3> four = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  EXPECT_THROW(fit_rbf(four, three), std::invalid_argument);
  EXPECT_THROW(rbf_interpolation_matrix(three, four), std::invalid_argument);
}

}  // namespace
}  // namespace facectl::face
