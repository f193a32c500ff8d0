#include "firmware-host/serve/face_geometry.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <exception>
#include <filesystem>
#include <initializer_list>

#include "control/face/reduced_face_model.hpp"
#include "facectl/face/face_model.hpp"
#include "facectl/face/rbf_morph.hpp"
#include "facectl/face/reduced_model_fit.hpp"

namespace facectl {
namespace {

using face::Vec3;

constexpr double kMmPerM = 1e3;

// Landmarks on bone that no muscle moves: the hairline, the top of the skull, the nose
// bridge and tip, the cheekbones, the eye corners and the condyles. Held still, they keep
// the upper skull from following the mouth's points through the interpolation's affine part.
constexpr std::initializer_list<const char*> kAnchors = {
    "fdp_11_1", "fdp_11_2", "fdp_11_3", "fdp_11_4", "fdp_9_15", "fdp_9_3",  "fdp_5_3",
    "fdp_5_4",  "fdp_3_7",  "fdp_3_8",  "fdp_3_11", "fdp_3_12", "fdp_2_13", "fdp_2_14"};

// Lines worth drawing between control points: the outer and inner lip contours, the brows.
constexpr std::initializer_list<std::initializer_list<const char*>> kContours = {
    {"fdp_8_4", "fdp_8_1", "fdp_8_3", "fdp_8_2", "fdp_8_4"},
    {"fdp_8_4", "fdp_2_2", "fdp_8_3", "fdp_2_3", "fdp_8_4"},
    {"fdp_4_6", "fdp_4_4", "fdp_4_2"},
    {"fdp_4_1", "fdp_4_3", "fdp_4_5"}};

struct NoGeometry {
  std::string why;
};

// The head's reduced model: the one the rig already evaluates, else its file.
std::shared_ptr<const face::ReducedFaceModel> reduced_model(const LoadedConfig& config,
                                                            const face::HeadSpec& spec,
                                                            const std::filesystem::path& dir) {
  if (config.built.model.mapping.reduced) return config.built.model.mapping.reduced;
  const std::filesystem::path file = dir / "reduced_face.txt";
  if (!std::filesystem::exists(file)) {
    throw NoGeometry{"the head has no reduced face model (" + file.string() +
                     "; `facectl face reduce` builds it)"};
  }
  return std::make_shared<const face::ReducedFaceModel>(
      face::load_reduced_model(file.string(), spec));
}

const face::LandmarkSpec* find_landmark(const face::HeadSpec& spec, const std::string& name) {
  for (const face::LandmarkSpec& l : spec.landmarks)
    if (l.name == name) return &l;
  return nullptr;
}

void append_mm(const Vec3& p, std::vector<double>& out) {
  for (int c = 0; c < 3; ++c) out.push_back(p[c] * kMmPerM);
}

void add_landmarks(const face::HeadSpec& spec, const face::TriMesh& skin, FaceGeometry& g,
                   std::vector<Vec3>& centers_mm) {
  for (const std::string& name : g.points) {
    const face::LandmarkSpec* l = find_landmark(spec, name);
    if (l == nullptr) {
      throw NoGeometry{spec.dir + "/landmarks.yaml: no landmark '" + name +
                       "' for the reduced model's control point"};
    }
    const Vec3 p = face::landmark_position(*l, skin.v);
    append_mm(p, g.points_mm);
    centers_mm.push_back(p * kMmPerM);
  }
  for (const char* name : kAnchors) {
    const bool is_point = std::find(g.points.begin(), g.points.end(), name) != g.points.end();
    const face::LandmarkSpec* l = find_landmark(spec, name);
    if (is_point || l == nullptr) continue;
    const Vec3 p = face::landmark_position(*l, skin.v);
    g.anchors.emplace_back(name);
    append_mm(p, g.anchors_mm);
    centers_mm.push_back(p * kMmPerM);
  }
}

// W: the interpolation's columns for the control points; the anchors' displacement is 0.
void add_skin(const face::TriMesh& skin, const std::vector<Vec3>& centers_mm, FaceGeometry& g) {
  std::vector<Vec3> vertices_mm;
  for (std::size_t i = 0; i < skin.v.size(); ++i) {
    vertices_mm.push_back(skin.v.get(i) * kMmPerM);
    append_mm(skin.v.get(i), g.vertices_mm);
  }
  for (const face::Tri& t : skin.tris) g.triangles.insert(g.triangles.end(), t.begin(), t.end());
  const Eigen::MatrixXd all = face::rbf_interpolation_matrix(centers_mm, vertices_mm);
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w =
      all.leftCols(static_cast<Eigen::Index>(g.points.size()));
  g.weights.assign(w.data(), w.data() + w.size());
}

void add_edges(FaceGeometry& g) {
  auto index = [&](const char* name) {
    return static_cast<int>(std::find(g.points.begin(), g.points.end(), name) - g.points.begin());
  };
  const int none = static_cast<int>(g.points.size());
  for (const auto& contour : kContours) {
    const std::vector<const char*> names(contour);
    for (std::size_t k = 1; k < names.size(); ++k) {
      const int a = index(names[k - 1]), b = index(names[k]);
      if (a != none && b != none) g.edges.push_back({a, b});
    }
  }
}

// Where each of the model's inputs is in a telemetry frame's face signals.
void add_signals(const FaceLayout& layout, FaceGeometry& g) {
  for (const std::string& muscle : g.reduced->muscles) {
    const auto i = layout.find(muscle);
    if (!i || *i >= layout.muscle_count()) {
      throw NoGeometry{"the reduced face model's muscle '" + muscle +
                       "' is not among head.muscles (rebuild it with `facectl face reduce`)"};
    }
    g.muscle_signals.push_back(*i);
  }
  g.jaw_pitch = layout.jaw_pitch();
  g.jaw_yaw = layout.jaw_yaw();
  g.jaw_protrusion = layout.jaw_protrusion();
  g.eyelid_closure[0] = layout.eyelid_closure(0);
  g.eyelid_closure[1] = layout.eyelid_closure(1);
}

}  // namespace

FaceGeometryLoad load_face_geometry(const LoadedConfig& config) {
  std::filesystem::path dir = std::filesystem::path(config.head.file).parent_path();
  if (dir.empty()) dir = ".";
  try {
    const face::HeadSpec spec = face::load_head_spec(dir.string());
    auto g = std::make_shared<FaceGeometry>();
    g->reduced = reduced_model(config, spec, dir);
    g->points = g->reduced->control_points;
    const face::TriMesh skin = face::read_base_skin(spec);
    std::vector<Vec3> centers_mm;
    add_landmarks(spec, skin, *g, centers_mm);
    add_skin(skin, centers_mm, *g);
    add_edges(*g);
    add_signals(config.built.model.layout, *g);
    return {std::move(g), ""};
  } catch (const NoGeometry& e) {
    return {nullptr, e.why};
  } catch (const std::exception& e) {
    return {nullptr, std::string("the face geometry did not load: ") + e.what()};
  }
}

}  // namespace facectl
