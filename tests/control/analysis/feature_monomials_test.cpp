// Drift guard: feature_monomials() must describe, column for column, the features the
// reduced face model evaluates. With an identity coefficient matrix, evaluate() returns
// the feature vector itself, so every column is compared on random inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "facectl/face/head_spec.hpp"
#include "facectl/face/reduced_model_fit.hpp"

namespace facectl::face {
namespace {

ReducedFaceModel shipped() {
  return load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt",
                            load_head_spec(FACECTL_DEFAULT_HEAD_DIR));
}

// m's coefficient matrix is replaced by the identity of the monomials' count.
void expect_monomials_match_features(ReducedFaceModel m, unsigned seed) {
  const std::vector<Monomial> monomials = feature_monomials(m);
  const int F = static_cast<int>(monomials.size()), n = static_cast<int>(m.muscles.size());
  m.coefficients = decltype(m.coefficients)::Identity(F, F);
  ReducedFaceWorkspace w = make_reduced_workspace(m);
  std::mt19937 rng(seed);
  // Beyond the admissible ranges too, so that a sign or a scale cannot hide.
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<double> x(static_cast<std::size_t>(n + 5)), features(static_cast<std::size_t>(F));
  for (int trial = 0; trial < 200; ++trial) {
    for (double& v : x) v = u(rng);
    x[n] *= 0.4;       // pitch, rad
    x[n + 1] *= 0.1;   // yaw, rad
    x[n + 2] *= 0.01;  // protrusion, m
    ReducedInput in{std::span<const double>(x).first(static_cast<std::size_t>(n)), x[n], x[n + 1],
                    x[n + 2]};
    in.eyelid_closure[0] = x[n + 3];  // the lids: variables n + 3 and n + 4
    in.eyelid_closure[1] = x[n + 4];
    evaluate(m, w, in, features);
    for (int k = 0; k < F; ++k) {
      const double expected = features[static_cast<std::size_t>(k)];
      const double got = evaluate_monomial(monomials[static_cast<std::size_t>(k)], x);
      ASSERT_NEAR(got, expected, 1e-14 * (1 + std::fabs(expected)))
          << "feature column " << k << " of " << F;
    }
  }
}

TEST(FeatureMonomials, DescribeEveryFeatureOfTheShippedModel) {
  const ReducedFaceModel m = shipped();
  ASSERT_EQ(static_cast<int>(feature_monomials(m).size()), m.feature_count());
  expect_monomials_match_features(m, 1);
}

TEST(FeatureMonomials, DescribeAnyFeatureList) {
  ReducedFaceModel m = shipped();
  const int one = constant_variable(m.muscles.size());
  // A muscle cubed, a wide pair, the jaw's three variables, a muscle by pitch squared, the
  // lids with each other, a muscle and the jaw; squared contractions: c⁴, c⁵, a square with
  // another muscle and with the jaw.
  const int lid_l = lid_variable(m.muscles.size(), 0), lid_r = lid_variable(m.muscles.size(), 1);
  const int sq3 = square_variable(m.muscles.size(), 3), sq7 = square_variable(m.muscles.size(), 7);
  m.features = {{5, 5, 5},       {0, 28, one},          {29, 30, 31},    {1, 29, 29},
                {30, 30, one},   {lid_l, lid_r, lid_r}, {2, lid_l, one}, {29, lid_r, one},
                {one, sq3, sq3}, {3, sq3, sq3},         {3, 5, sq7},     {29, one, sq7}};
  expect_monomials_match_features(m, 2);
}

TEST(FeatureMonomials, PowersAreAscendingAndPositive) {
  const ReducedFaceModel m = shipped();
  for (const Monomial& mono : feature_monomials(m)) {
    for (std::size_t k = 0; k < mono.powers.size(); ++k) {
      EXPECT_GE(mono.powers[k][1], 1);
      EXPECT_LT(mono.powers[k][0], constant_variable(m.muscles.size()));  // no square left
      if (k > 0) {
        EXPECT_LT(mono.powers[k - 1][0], mono.powers[k][0]);
      }
    }
  }
}

TEST(FeatureMonomials, AFactorBeyondTheVariablesIsRefused) {
  ReducedFaceModel m = shipped();
  const int one = constant_variable(m.muscles.size());
  m.features = {{0, one, variable_count(m.muscles.size())}};
  EXPECT_THROW(feature_monomials(m), std::out_of_range);
  m.features = {{-1, one, one}};
  EXPECT_THROW(feature_monomials(m), std::out_of_range);
}

}  // namespace
}  // namespace facectl::face
