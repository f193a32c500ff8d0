// The face the console draws: the reduced model's control points, the skin at rest and the
// RBF weights W that carry the points' displacements onto it, and the per-stream
// evaluation of the reduced model behind telemetry's `landmarks_mm`.
#include "firmware-host/serve/face_geometry.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "control/face/reduced_face_model.hpp"
#include "facectl/face/rbf_morph.hpp"
#include "firmware-host/serve/face_landmarks.hpp"
#include "tests/firmware-host/serve/served_head.hpp"

namespace facectl {
namespace {

const LoadedConfig& shipped() {
  static const LoadedConfig config =
      load_config(std::string(FACECTL_SOURCE_DIR) + "/config/facectl.yaml");
  return config;
}

const FaceGeometry& geometry() {
  static const FaceGeometryLoad load = load_face_geometry(shipped());
  if (!load.geometry) ADD_FAILURE() << load.why_not;
  return *load.geometry;
}

std::vector<face::Vec3> triples(const std::vector<double>& mm) {
  std::vector<face::Vec3> out;
  for (std::size_t i = 0; i + 2 < mm.size(); i += 3) out.emplace_back(mm[i], mm[i + 1], mm[i + 2]);
  return out;
}

// The skin vertex at `p` (mm), if a landmark lies on one exactly; else -1.
int vertex_at(const FaceGeometry& g, const face::Vec3& p) {
  const auto v = triples(g.vertices_mm);
  for (std::size_t i = 0; i < v.size(); ++i)
    if ((v[i] - p).norm() < 1e-9) return static_cast<int>(i);
  return -1;
}

double weight(const FaceGeometry& g, int vertex, std::size_t point) {
  return g.weights[static_cast<std::size_t>(vertex) * g.points.size() + point];
}

TEST(FaceGeometry, DescribesTheReducedModelsPointsAndTheSkin) {
  const FaceGeometry& g = geometry();
  EXPECT_EQ(g.points, shipped().built.model.mapping.reduced->control_points);
  EXPECT_EQ(g.points_mm.size(), 3 * g.points.size());
  EXPECT_GT(g.vertices_mm.size(), 3u * 400);
  EXPECT_EQ(g.triangles.size() % 3, 0u);
  const int vertices = static_cast<int>(g.vertices_mm.size() / 3);
  EXPECT_TRUE(std::all_of(g.triangles.begin(), g.triangles.end(),
                          [&](int v) { return v >= 0 && v < vertices; }));
  EXPECT_EQ(g.weights.size(), g.vertices_mm.size() / 3 * g.points.size());
  EXPECT_FALSE(g.edges.empty());
  // Millimetres: the shipped face is some 150 mm wide, not 0.15.
  const auto x = triples(g.vertices_mm);
  const auto [lo, hi] =
      std::minmax_element(x.begin(), x.end(), [](auto& a, auto& b) { return a.x() < b.x(); });
  EXPECT_GT(hi->x() - lo->x(), 100.0);
}

// W at a vertex that is a control point is that point's unit row; at an anchor, zero.
TEST(FaceGeometry, WeightsAreExactAtTheControlPointsAndZeroAtTheAnchors) {
  const FaceGeometry& g = geometry();
  const auto points = triples(g.points_mm);
  int checked = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const int v = vertex_at(g, points[p]);
    if (v < 0) continue;
    ++checked;
    for (std::size_t q = 0; q < points.size(); ++q)
      EXPECT_NEAR(weight(g, v, q), p == q ? 1.0 : 0.0, 1e-9) << g.points[p] << " " << g.points[q];
  }
  EXPECT_EQ(checked, static_cast<int>(points.size()));  // each is one skin vertex
  checked = 0;
  for (const face::Vec3& a : triples(g.anchors_mm)) {
    const int v = vertex_at(g, a);
    if (v < 0) continue;  // an anchor off the skin (condyles, top of the skull)
    ++checked;
    for (std::size_t q = 0; q < points.size(); ++q) EXPECT_NEAR(weight(g, v, q), 0.0, 1e-9);
  }
  EXPECT_GE(checked, 8);
  EXPECT_TRUE(std::find(g.anchors.begin(), g.anchors.end(), "fdp_11_1") != g.anchors.end());
}

// W is the control points' columns of the interpolation through points and anchors, whose
// affine part moves every vertex by c when every point and anchor moves by c.
TEST(FaceGeometry, AConstantDisplacementOfAllPointsMovesEveryVertexByIt) {
  const FaceGeometry& g = geometry();
  std::vector<face::Vec3> centers = triples(g.points_mm);
  for (const face::Vec3& a : triples(g.anchors_mm)) centers.push_back(a);
  const Eigen::MatrixXd all = face::rbf_interpolation_matrix(centers, triples(g.vertices_mm));
  const Eigen::Vector3d c(1.5, -2.0, 0.75);
  const Eigen::MatrixX3d moved = all * Eigen::VectorXd::Ones(all.cols()) * c.transpose();
  for (Eigen::Index v = 0; v < all.rows(); ++v) {
    ASSERT_LT((moved.row(v).transpose() - c).norm(), 1e-9) << "vertex " << v;
    for (std::size_t p = 0; p < g.points.size(); ++p)
      ASSERT_EQ(all(v, static_cast<Eigen::Index>(p)), weight(g, static_cast<int>(v), p));
  }
}

TEST(FaceGeometry, AHeadWithoutAReducedModelHasNone) {
  testing::TempDir dir;
  const LoadedConfig config = load_config(
      testing::copied_head_config(dir, testing::kTermsOnlyRig, /*with_reduced_model=*/false));
  const FaceGeometryLoad load = load_face_geometry(config);
  EXPECT_EQ(load.geometry, nullptr);
  EXPECT_NE(load.why_not.find("reduced_face.txt"), std::string::npos) << load.why_not;
}

// A rig that reads no control points (linear terms only) carries no reduced model in its
// controller model: the geometry loads it from the head's folder.
TEST(FaceGeometry, LoadsTheReducedModelForARigThatReadsNoPoints) {
  testing::TempDir dir;
  const LoadedConfig config = load_config(
      testing::copied_head_config(dir, testing::kTermsOnlyRig, /*with_reduced_model=*/true));
  ASSERT_EQ(config.built.model.mapping.reduced, nullptr);
  const FaceGeometryLoad load = load_face_geometry(config);
  ASSERT_NE(load.geometry, nullptr) << load.why_not;
  EXPECT_EQ(load.geometry->points, geometry().points);
}

// The displacements of a frame are face::evaluate's, in mm, and a smile's left lip corner
// (fdp_8_3) moves up and out (+x is the head's left) from where neutral has it.
TEST(FaceLandmarks, ASmileMovesTheLeftLipCornerUpAndOut) {
  const ControllerModel& m = shipped().built.model;
  const auto g = load_face_geometry(shipped()).geometry;
  ASSERT_NE(g, nullptr);
  FaceLandmarks landmarks(g);
  std::vector<double> signals(m.neutral.begin(), m.neutral.begin() + m.layout.size());
  const std::vector<double> neutral(landmarks.displacements_mm(signals).begin(),
                                    landmarks.displacements_mm(signals).end());
  const std::size_t zyg = *m.layout.find("zygomaticus_major_l");
  signals[zyg] = 1.0;
  signals[m.layout.jaw_pitch()] = 0.05;       // rad: the jaw's input reaches the model too
  signals[m.layout.eyelid_closure(0)] = 0.6;  // and the lids' do
  const auto smile = landmarks.displacements_mm(signals);

  face::ReducedFaceWorkspace w = face::make_reduced_workspace(*g->reduced);
  std::vector<double> expected(3 * g->points.size());
  face::ReducedInput in{std::span(signals).first(m.layout.muscle_count()),
                        signals[m.layout.jaw_pitch()], signals[m.layout.jaw_yaw()],
                        signals[m.layout.jaw_protrusion()]};
  in.eyelid_closure[0] = signals[m.layout.eyelid_closure(0)];
  in.eyelid_closure[1] = signals[m.layout.eyelid_closure(1)];
  face::evaluate(*g->reduced, w, in, expected);
  ASSERT_EQ(smile.size(), expected.size());
  for (std::size_t i = 0; i < smile.size(); ++i) EXPECT_NEAR(smile[i], expected[i] * 1e3, 1e-9);

  const std::size_t corner =
      std::find(g->points.begin(), g->points.end(), "fdp_8_3") - g->points.begin();
  ASSERT_LT(corner, g->points.size());
  EXPECT_GT(smile[3 * corner] - neutral[3 * corner], 0.5);          // out, mm
  EXPECT_GT(smile[3 * corner + 1] - neutral[3 * corner + 1], 0.5);  // up, mm
}

}  // namespace
}  // namespace facectl
