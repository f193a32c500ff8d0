// The folded control-point sources must equal what they replace: the sum over
// an actuator's point terms of gain · (axis · the point's displacement from the
// reduced face model), on random inputs.
#include "control/mapping/point_projection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include "control/mapping/rig_mapping.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/reduced_model_fit.hpp"

namespace facectl {
namespace {

TEST(PointProjection, EqualsTheSumOfItsPointTermsOverTheDisplacements) {
  const face::ReducedFaceModel m = face::load_reduced_model(
      FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt", face::load_head_spec(FACECTL_DEFAULT_HEAD_DIR));
  const std::size_t points = m.control_points.size(), n = m.muscles.size();
  ASSERT_GE(points, 3u);
  // Actuator 4 reads two points on two axes; actuator 1 one point; actuator 7
  // the same point as actuator 4, so the rows must not share storage.
  const std::vector<PointTerm> terms = {{4, 0, {0, 1, 0}, 1.8},
                                        {4, 0, {1, 0, 0}, 0.6},
                                        {4, points - 1, {0, 0.6, 0.8}, -2.5},
                                        {1, 2, {0, 0, 1}, 3.0},
                                        {7, 0, {0, 1, 0}, 1.0}};
  const PointProjection p = project_point_terms(m, terms);
  ASSERT_EQ(p.actuator, (std::vector<std::size_t>{4, 1, 7}));

  face::ReducedFaceWorkspace w = face::make_reduced_workspace(m);
  std::vector<double> c(n), displacement(3 * points);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    for (double& v : c) v = u(rng);
    face::ReducedInput in{c, 0.3 * u(rng), 0.08 * (u(rng) - 0.5), 0.008 * u(rng)};
    in.eyelid_closure[0] = u(rng);
    in.eyelid_closure[1] = u(rng);
    face::evaluate(m, w, in, displacement);
    std::array<double, 8> expected{};
    for (const PointTerm& t : terms) {
      const double* d = displacement.data() + 3 * t.point;
      expected[t.actuator] += t.gain * (d[0] * t.axis[0] + d[1] * t.axis[1] + d[2] * t.axis[2]);
    }
    face::evaluate_features(m, w, in);
    const Eigen::VectorXd got = p.rows * w.features;
    for (std::size_t r = 0; r < p.actuator.size(); ++r) {
      const double e = expected[p.actuator[r]];
      ASSERT_NEAR(got[static_cast<Eigen::Index>(r)], e, 1e-12 * (1.0 + std::fabs(e)))
          << "actuator " << p.actuator[r] << ", trial " << trial;
    }
  }
}

// The tick's path (finish_points, make_mapping_workspace, evaluate_control_points,
// over the projection's feature subset) against the dense rows over every feature,
// with an actuator whose point terms all have zero gain (a row of zeros: no columns).
TEST(PointProjection, TheTickEvaluatesTheDenseRowsOverTheFeatureSubset) {
  const auto model = std::make_shared<const face::ReducedFaceModel>(
      face::load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt",
                               face::load_head_spec(FACECTL_DEFAULT_HEAD_DIR)));
  const std::size_t n = model->muscles.size();
  RigMapping map;
  map.linear = LinearMapping(4, n + 5);
  map.transforms.resize(4);
  map.reduced = model;
  map.muscle_count = n;
  map.jaw_pitch = n, map.jaw_yaw = n + 1, map.jaw_protrusion = n + 2;
  map.eyelid_closure[0] = n + 3, map.eyelid_closure[1] = n + 4;
  map.points = {{0, 0, {0, 1, 0}, 1.8},
                {0, 0, {1, 0, 0}, 0.6},
                {2, 1, {0, 1, 0}, 1.8},
                {2, 1, {-1, 0, 0}, 0.6},
                {3, 4, {0, 0, 1}, 0.0}};
  finish_points(map);
  ASSERT_EQ(map.projection.actuator, (std::vector<std::size_t>{0, 2, 3}));
  MappingWorkspace w = make_mapping_workspace(map);
  face::ReducedFaceWorkspace full = face::make_reduced_workspace(*model);

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::array<double, kMaxFaceSignals> face{};
  for (int trial = 0; trial < 100; ++trial) {
    for (std::size_t i = 0; i < n; ++i) face[i] = u(rng);
    face[n] = 0.3 * u(rng), face[n + 1] = 0.08 * (u(rng) - 0.5), face[n + 2] = 0.008 * u(rng);
    face[n + 3] = u(rng), face[n + 4] = u(rng);
    evaluate_control_points(map, w, face);
    face::ReducedInput in{std::span<const double>(face.data(), n), face[n], face[n + 1],
                          face[n + 2]};
    in.eyelid_closure[0] = face[n + 3];
    in.eyelid_closure[1] = face[n + 4];
    face::evaluate_features(*model, full, in);
    const Eigen::VectorXd dense = map.projection.rows * full.features;
    for (std::size_t r = 0; r < 3; ++r) {
      const double e = dense[static_cast<Eigen::Index>(r)];
      ASSERT_NEAR(w.point_effector[r], e, 1e-13 * (1.0 + std::fabs(e))) << "row " << r;
    }
    ASSERT_EQ(w.point_effector[2], 0.0);  // the zero-gain actuator
  }
}

TEST(PointProjection, AWorkspaceForAModelOfOtherMusclesIsRefused) {
  RigMapping map;
  map.linear = LinearMapping(1, 40);
  map.transforms.resize(1);
  map.reduced = std::make_shared<const face::ReducedFaceModel>(
      face::load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt",
                               face::load_head_spec(FACECTL_DEFAULT_HEAD_DIR)));
  map.muscle_count = map.reduced->muscles.size() - 1;
  map.points = {{0, 0, {0, 1, 0}, 1.0}};
  finish_points(map);
  EXPECT_THROW(make_mapping_workspace(map), std::logic_error);
}

}  // namespace
}  // namespace facectl
