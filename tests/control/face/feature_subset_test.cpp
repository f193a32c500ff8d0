// A feature subset must give exactly the columns it names of the full feature
// vector (the rig mapping's control-point rows use it in the tick), and the
// point projection's weights over it must equal its rows over all features.
#include "control/face/feature_subset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "control/mapping/point_projection.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/reduced_model_fit.hpp"

namespace facectl::face {
namespace {

ReducedFaceModel shipped() {
  return load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt",
                            load_head_spec(FACECTL_DEFAULT_HEAD_DIR));
}

struct Input {
  std::vector<double> contractions;
  double pitch = 0, yaw = 0, protrusion = 0, lid_l = 0, lid_r = 0;
  ReducedInput reduced() const {
    ReducedInput r{contractions, pitch, yaw, protrusion};
    r.eyelid_closure[0] = lid_l;
    r.eyelid_closure[1] = lid_r;
    return r;
  }
};

Input random_input(std::size_t muscles, std::mt19937& rng) {
  // Beyond the admissible ranges and signed, so that a sign or a scale cannot hide.
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  Input in;
  in.contractions.resize(muscles);
  for (double& c : in.contractions) c = u(rng);
  in.pitch = 0.4 * u(rng);
  in.yaw = 0.1 * u(rng);
  in.protrusion = 0.01 * u(rng);
  in.lid_l = u(rng);
  in.lid_r = u(rng);
  return in;
}

void expect_every_column_bit_for_bit(const ReducedFaceModel& m, unsigned seed) {
  std::vector<int> all(static_cast<std::size_t>(m.feature_count()));
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(all.size() - 1 - k);
  const FeatureSubset s = select_features(m, all);  // given in reverse: sorted
  ASSERT_EQ(s.columns.size(), all.size());
  FeatureSubsetWorkspace sw = make_subset_workspace(s);
  ReducedFaceWorkspace w = make_reduced_workspace(m);
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    const Input in = random_input(m.muscles.size(), rng);
    evaluate_features(m, w, in.reduced());
    evaluate_features(s, sw, in.reduced());
    for (std::size_t k = 0; k < s.columns.size(); ++k) {
      ASSERT_EQ(s.columns[k], static_cast<int>(k));
      // Bit for bit: the tick's values must not depend on which path made them.
      ASSERT_EQ(sw.values[static_cast<Eigen::Index>(k)], w.features[s.columns[k]])
          << "feature column " << k << ", trial " << trial;
    }
  }
}

TEST(FeatureSubset, EveryColumnEqualsTheFullFeatureVectorBitForBit) {
  expect_every_column_bit_for_bit(shipped(), 1);
}

TEST(FeatureSubset, AnyFeatureListToo) {
  ReducedFaceModel m = shipped();
  const int one = constant_variable(m.muscles.size());
  // A muscle cubed, a wide pair, the jaw alone and with a muscle, both lids, a lid with a
  // muscle and with the jaw, the constant.
  const int lid_l = lid_variable(m.muscles.size(), 0), lid_r = lid_variable(m.muscles.size(), 1);
  m.features = {{5, 5, 5},           {0, 28, one},      {29, 30, 31},     {1, 29, 29},
                {lid_l, lid_r, one}, {3, lid_l, lid_l}, {29, lid_r, one}, {one, one, one}};
  m.coefficients.resize(m.coefficients.rows(), static_cast<Eigen::Index>(m.features.size()));
  expect_every_column_bit_for_bit(m, 2);
}

TEST(FeatureSubset, DuplicatesAreDroppedAndAMissingColumnIsRefused) {
  const ReducedFaceModel m = shipped();
  const FeatureSubset s = select_features(m, {7, 3, 7});
  EXPECT_EQ(s.columns, (std::vector<int>{3, 7}));
  EXPECT_THROW(select_features(m, {m.feature_count()}), std::out_of_range);
  EXPECT_THROW(select_features(m, {-1}), std::out_of_range);
}

TEST(FeatureSubset, TheProjectionWeighsOnlyItsNonZeroColumnsAndLosesNothing) {
  const ReducedFaceModel m = shipped();
  const std::vector<PointTerm> terms = {{4, 0, {0, 1, 0}, 1.8},
                                        {4, 0, {1, 0, 0}, 0.6},
                                        {1, 1, {0, 1, 0}, 1.8},
                                        {1, 1, {-1, 0, 0}, 0.6}};
  const PointProjection p = project_point_terms(m, terms);
  // Every column left out is zero in every row; every column kept is not.
  std::size_t kept = 0;
  for (Eigen::Index k = 0; k < p.rows.cols(); ++k) {
    const bool used = (p.rows.col(k).array() != 0.0).any();
    const bool in_subset =
        kept < p.features.columns.size() && p.features.columns[kept] == static_cast<int>(k);
    ASSERT_EQ(used, in_subset) << "column " << k;
    if (in_subset) ++kept;
  }
  // The shipped head fits each point on the muscles that move it: far fewer columns.
  EXPECT_LT(2 * p.features.columns.size(), static_cast<std::size_t>(m.feature_count()));

  FeatureSubsetWorkspace sw = make_subset_workspace(p.features);
  ReducedFaceWorkspace w = make_reduced_workspace(m);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const Input in = random_input(m.muscles.size(), rng);
    evaluate_features(m, w, in.reduced());
    evaluate_features(p.features, sw, in.reduced());
    const Eigen::VectorXd dense = p.rows * w.features;
    const Eigen::VectorXd compact = p.weights * sw.values;
    for (Eigen::Index r = 0; r < dense.size(); ++r) {
      // Only the order of the sum differs.
      ASSERT_NEAR(compact[r], dense[r], 1e-13 * (1.0 + std::fabs(dense[r])))
          << "row " << r << ", trial " << trial;
    }
  }
}

}  // namespace
}  // namespace facectl::face
