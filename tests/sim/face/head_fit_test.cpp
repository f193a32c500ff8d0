// `facectl face fit-head` as a library (head_fit.hpp, head_writer.hpp) on the synthetic
// test heads of test_heads.hpp: landmark placement against the warp's truth, the written
// folder loads and builds, expressions move it the expected way, and unusable meshes are
// refused naming what is wrong.
#include "facectl/face/head_fit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>

#include "default_head.hpp"
#include "facectl/face/head_writer.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/obj_io.hpp"
#include "facectl/face/steady_state.hpp"
#include "test_heads.hpp"

namespace facectl::face {
namespace {

using testing::default_spec;

const TriMesh& source_skin() {
  static const TriMesh m = read_obj(default_spec().skin_file, default_spec().skin_scale);
  return m;
}

struct Fitted {
  testing::HeadWarp warp;
  TriMesh target;
  HeadFit fit;
};

const Fitted& fitted(int i) {
  static std::map<int, Fitted> cache;
  auto it = cache.find(i);
  if (it == cache.end()) {
    Fitted f;
    f.warp = testing::test_head_warps()[static_cast<std::size_t>(i)];
    f.target = testing::make_test_head(default_spec(), f.warp);
    f.fit = fit_head(default_spec(), source_skin(), f.target, HeadFitOptions{});
    it = cache.emplace(i, std::move(f)).first;
  }
  return it->second;
}

// Placement error per landmark: the placed point (mean of its vertices + offset) against
// where the warp puts the default's landmark. On the split heads the truth of a skin
// landmark is a vertex; on the resampled grid_narrow it is not, so its skin landmarks are
// judged by the excess over the distance from the truth to the nearest target vertex
// (what no placement on vertices can beat). Measured (docs/FACE_MODEL.md, "Bringing your
// own head"): split heads 1.63 mm skin (an outer lip corner), 4.53 mm bone (7.1, 16 cm
// from the skin, where G extrapolates), 4.90 mm muscle corner; grid_narrow 5.2 mm skin
// excess (gonion_l, at the steep side of the mask), 16.6 mm bone (7.1), 8.4 mm muscle
// corner. Bounds with about 50 % margin; a landmark one vertex off would be ~6 mm.
struct Bounds {
  double skin_excess, bone, muscle;
};
Bounds bounds(const testing::HeadWarp& w) {
  return w.grid > 0 ? Bounds{7.5, 25.0, 12.5} : Bounds{2.5, 6.0, 7.5};
}

// The fitted head written as `facectl face fit-head` writes it, under the test's temporary
// folder; returns the head folder.
std::string write_fitted_folder(const Fitted& f, const std::string& tag) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / (tag + f.warp.name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "in");
  const std::string obj = (dir / "in" / "head.obj").string();
  write_obj(obj, f.target, f.warp.units);
  const std::string units = f.warp.units == 0.01 ? "cm" : "mm";
  write_head_folder((dir / "head").string(), f.fit.spec,
                    {obj, units, FACECTL_DEFAULT_HEAD_DIR, "test head"});
  return (dir / "head").string();
}

class HeadFitOnTestHead : public ::testing::TestWithParam<int> {};

TEST_P(HeadFitOnTestHead, PlacesLandmarksNearTheWarpedTruth) {
  const Fitted& f = fitted(GetParam());
  EXPECT_TRUE(f.fit.problems.empty()) << f.fit.problems.front();
  EXPECT_TRUE(f.fit.converged);
  ASSERT_EQ(f.target.v.size(), static_cast<std::size_t>(f.warp.vertices));
  double worst_skin = 0, worst_excess = 0, worst_bone = 0;
  std::vector<double> skin, floors;
  std::string worst_name, over;  // every landmark off by more than 1 mm, for failures
  for (std::size_t i = 0; i < default_spec().landmarks.size(); ++i) {
    const LandmarkSpec& src = default_spec().landmarks[i];
    const LandmarkSpec& placed = f.fit.spec.landmarks[i];
    const Vec3 truth = testing::true_landmark(default_spec(), source_skin(), src, f.warp);
    const double e = (landmark_position(placed, f.target.v) - truth).norm() * 1e3;
    if (e > 1.0) over += " " + src.name + "=" + std::to_string(e);
    if (src.offset.norm() > 0) {
      worst_bone = std::max(worst_bone, e);
      continue;
    }
    double floor = 0;  // a one-vertex landmark: to the nearest target vertex
    if (src.vertices.size() == 1) {
      floor = std::numeric_limits<double>::infinity();
      for (std::size_t v = 0; v < f.target.v.size(); ++v)
        floor = std::min(floor, (f.target.v.get(v) - truth).norm() * 1e3);
    }
    skin.push_back(e);
    floors.push_back(floor);
    worst_skin = std::max(worst_skin, e);
    if (e - floor > worst_excess) {
      worst_excess = e - floor;
      worst_name = src.name;
    }
  }
  auto median = [](std::vector<double> x) {
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    return x[x.size() / 2];
  };
  RecordProperty("worst_skin_mm", std::to_string(worst_skin));
  RecordProperty("median_skin_mm", std::to_string(median(skin)));
  RecordProperty("median_nearest_vertex_mm", std::to_string(median(floors)));
  RecordProperty("worst_skin_excess_mm", std::to_string(worst_excess));
  RecordProperty("worst_skin_landmark", worst_name);
  RecordProperty("worst_bone_mm", std::to_string(worst_bone));
  EXPECT_LT(worst_excess, bounds(f.warp).skin_excess)
      << f.warp.name << ": worst skin landmark " << worst_name << "; over 1 mm:" << over;
  EXPECT_LT(worst_bone, bounds(f.warp).bone) << f.warp.name;
  EXPECT_LT(f.fit.last_change_mm, 0.5);
}

TEST_P(HeadFitOnTestHead, WrittenFolderBuildsAndMovesAsExpected) {
  const Fitted& f = fitted(GetParam());
  const HeadSpec spec = load_head_spec(write_fitted_folder(f, "fit_head_"));
  const FaceModel m = build_face_model(spec);
  EXPECT_EQ(m.skin.v.size(), f.target.v.size());
  const ExpressionLibrary lib =
      load_expression_library(FACECTL_CONFIG_DIR "/expressions/library.yaml", spec);
  SteadyStateOptions so;
  so.max_frames = 250;
  so.tolerance_mm = 0.05;
  auto settle = [&](const char* name, const char* landmark) {
    FaceData d = make_face_data(m);
    const int l = m.landmark_index(landmark);
    const Vec3 rest = landmark_position(m, d.skin_x, l);
    run_to_steady_state(m, d, face_input(*lib.find(name)), so);
    return Vec3(landmark_position(m, d.skin_x, l) - rest);
  };
  // Joy raises the lip corners; an open jaw lowers the chin.
  const double joy_l = settle("joy", "fdp_8_3").y(), joy_r = settle("joy", "fdp_8_4").y();
  const double jaw = settle("jaw_open", "fdp_2_1").y();
  RecordProperty("joy_lift_mm", std::to_string(joy_l * 1e3) + " " + std::to_string(joy_r * 1e3));
  RecordProperty("jaw_open_chin_mm", std::to_string(jaw * 1e3));
  // Both corners rise, and well together. Not always evenly: grid_narrow's rise 4.4 and
  // 8.6 mm here (4.5 and 8.9 settled), its corner vertices riding on different muscles on
  // the two sides, and a muscle's shape can jump with its corners (docs/FACE_MODEL.md,
  // "Bringing your own head" and Known issues, "Muscle shapes jump").
  EXPECT_GT(joy_l, 0.2e-3);
  EXPECT_GT(joy_r, 0.2e-3);
  EXPECT_GT(joy_l + joy_r, 4e-3);
  EXPECT_LT(jaw, -3e-3);
}

// The skin's stiffnesses are rescaled to the head's vertex density for its size
// (skin_density.hpp). With the default head's per-vertex values, grid_narrow (3.2 times
// the default's vertices for its size) settled none of these six in 3000 frames and
// long_wide_jaw (2.8 times) not joy or sadness; scaled, each settles in 374-1434 frames
// (docs/FACE_MODEL.md, "Skin stiffness per unit area").
TEST_P(HeadFitOnTestHead, LibraryExpressionsSettleOnTheFittedHead) {
  const Fitted& f = fitted(GetParam());
  EXPECT_LT(f.fit.vertex_area_ratio, 0.7) << "every test head is denser than the default";
  EXPECT_NEAR(f.fit.spec.skin.anchor,
              default_spec().skin.anchor * f.fit.vertex_area_ratio * f.fit.vertex_area_ratio,
              1e-12);
  const HeadSpec spec = load_head_spec(write_fitted_folder(f, "settle_"));
  EXPECT_DOUBLE_EQ(spec.skin.stretch, f.fit.spec.skin.stretch) << "face.yaml keeps the scaling";
  const FaceModel m = build_face_model(spec);
  const ExpressionLibrary lib =
      load_expression_library(FACECTL_CONFIG_DIR "/expressions/library.yaml", spec);
  SteadyStateOptions so;
  so.max_frames = 3000;
  for (const char* name : {"joy", "sadness", "anger", "fear", "disgust", "surprise"}) {
    FaceData d = make_face_data(m);
    const SteadyStateResult r = run_to_steady_state(m, d, face_input(*lib.find(name)), so);
    EXPECT_TRUE(r.converged) << f.warp.name << " " << name << ": residual " << r.residual_mm
                             << " mm after " << r.frames << " frames";
  }
}

// Muscle corners (landmark + offset, up to 22 mm under the skin) carried by G against the
// warp of the default's corners; bounds above.
TEST_P(HeadFitOnTestHead, CarriesMuscleCornersNearTheWarpedTruth) {
  const Fitted& f = fitted(GetParam());
  std::map<std::string, const LandmarkSpec*> by_name;
  for (const LandmarkSpec& l : default_spec().landmarks) by_name[l.name] = &l;
  double worst = 0;
  std::string worst_muscle;
  for (const MuscleSpec& m : default_spec().muscles)
    for (const auto* refs : {&m.origin, &m.insertion, &m.inner, &m.outer})
      for (const PointRef& r : *refs) {
        const Vec3 p = landmark_position(*by_name[r.landmark], source_skin().v) + r.offset;
        const double e = (f.fit.morph.apply(p) - f.warp.apply(p)).norm() * 1e3;
        if (e > worst) {
          worst = e;
          worst_muscle = m.name;
        }
      }
  RecordProperty("worst_muscle_corner_mm", std::to_string(worst));
  EXPECT_LT(worst, bounds(f.warp).muscle) << f.warp.name << ": " << worst_muscle;
}

// The same mesh with its vertices renumbered, each face's corners rotated (the winding
// kept) and the faces reordered fits to the same head, to the last bit: before the fit ran
// on a canonical numbering, four orders of broad_short gave muscle corners up to 0.31 mm
// apart, and one of them smiled lopsidedly (docs/FACE_MODEL.md, "Known issues").
TEST_P(HeadFitOnTestHead, TheMeshsNumberingDoesNotChangeTheFit) {
  const Fitted& f = fitted(GetParam());
  // The renumbered mesh's vertex k is the target's old_of[k].
  const testing::Renumbered r = testing::renumbered(f.target, 7, true);
  const std::vector<int>& old_of = r.old_of;
  const HeadFit g = fit_head(default_spec(), source_skin(), r.mesh, HeadFitOptions{});
  auto in_target = [&](std::vector<int> v) {
    for (int& i : v) i = old_of[static_cast<std::size_t>(i)];
    return v;
  };
  EXPECT_EQ(g.iterations, f.fit.iterations);
  EXPECT_EQ(g.refined_pairs, f.fit.refined_pairs);
  ASSERT_EQ(g.spec.landmarks.size(), f.fit.spec.landmarks.size());
  for (std::size_t i = 0; i < g.spec.landmarks.size(); ++i) {
    const LandmarkSpec &a = f.fit.spec.landmarks[i], &b = g.spec.landmarks[i];
    EXPECT_EQ(in_target(b.vertices), a.vertices) << a.name;
    EXPECT_EQ(b.offset, a.offset) << a.name;
    // What the report and the console table print.
    EXPECT_EQ(in_target(g.landmarks[i].vertices), f.fit.landmarks[i].vertices) << a.name;
  }
  ASSERT_EQ(g.spec.openings.size(), f.fit.spec.openings.size());
  for (std::size_t i = 0; i < g.spec.openings.size(); ++i)
    EXPECT_EQ(in_target(g.spec.openings[i].second), f.fit.spec.openings[i].second)
        << f.fit.spec.openings[i].first;
  ASSERT_EQ(g.spec.muscles.size(), f.fit.spec.muscles.size());
  for (std::size_t m = 0; m < g.spec.muscles.size(); ++m) {
    const MuscleSpec &a = f.fit.spec.muscles[m], &b = g.spec.muscles[m];
    for (const auto& [ra, rb] : {std::pair{&a.origin, &b.origin},
                                 {&a.insertion, &b.insertion},
                                 {&a.inner, &b.inner},
                                 {&a.outer, &b.outer}}) {
      ASSERT_EQ(ra->size(), rb->size()) << a.name;
      for (std::size_t k = 0; k < ra->size(); ++k) {
        EXPECT_EQ((*rb)[k].landmark, (*ra)[k].landmark) << a.name;
        EXPECT_EQ((*rb)[k].offset, (*ra)[k].offset) << a.name << ", corner " << k;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    TestHeads, HeadFitOnTestHead, ::testing::Values(0, 1, 2), [](const auto& p) {
      return testing::test_head_warps()[static_cast<std::size_t>(p.param)].name;
    });

// The committed test heads are what the generator (make_test_heads) writes today.
TEST(TestHeads, CommittedMeshesMatchTheGenerator) {
  const std::filesystem::path tmp = std::filesystem::path(::testing::TempDir()) / "test_heads";
  std::filesystem::create_directories(tmp);
  auto text = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const testing::HeadWarp& w : testing::test_head_warps()) {
    const TriMesh m = testing::make_test_head(default_spec(), w);
    EXPECT_EQ(m.v.size(), static_cast<std::size_t>(w.vertices)) << w.name;
    write_obj((tmp / (w.name + ".obj")).string(), m, w.units);
    const std::string committed = text(std::filesystem::path(FACECTL_CONFIG_DIR) / ".." /
                                       "tests/data/heads" / w.name / "skin.obj");
    EXPECT_FALSE(committed.empty()) << w.name;
    EXPECT_TRUE(text(tmp / (w.name + ".obj")) == committed)
        << w.name << ": regenerate with make_test_heads config/heads/default tests/data/heads";
  }
}

// The default skin onto itself (closed over the mouth and eyes, so the openings are
// joined along edges): every landmark and opening comes back, muscle corners stay put.
TEST(HeadFit, DefaultOntoItselfIsTheIdentity) {
  const HeadFit f = fit_head(default_spec(), source_skin(), source_skin(), HeadFitOptions{});
  EXPECT_TRUE(f.problems.empty());
  for (std::size_t i = 0; i < default_spec().landmarks.size(); ++i) {
    EXPECT_EQ(f.spec.landmarks[i].vertices, default_spec().landmarks[i].vertices)
        << default_spec().landmarks[i].name;
    EXPECT_LT((f.spec.landmarks[i].offset - default_spec().landmarks[i].offset).norm(), 1e-6);
  }
  for (std::size_t i = 0; i < default_spec().openings.size(); ++i) {
    auto a = f.spec.openings[i].second, b = default_spec().openings[i].second;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << default_spec().openings[i].first;
  }
  for (std::size_t m = 0; m < default_spec().muscles.size(); ++m)
    for (std::size_t k = 0; k < 2 && k < default_spec().muscles[m].origin.size(); ++k)
      EXPECT_LT(
          (f.spec.muscles[m].origin[k].offset - default_spec().muscles[m].origin[k].offset).norm(),
          1e-6);
  EXPECT_NEAR(f.size_ratio, 1.0, 1e-12);
  EXPECT_NEAR(f.vertex_area_ratio, 1.0, 1e-12);
  EXPECT_NEAR(f.spec.skin.anchor, default_spec().skin.anchor, 1e-12);
  EXPECT_NEAR(f.spec.skin.stretch, default_spec().skin.stretch, 1e-12);
}

// The model has no length of its own: the default skin half as large again is the same
// mesh for its size, and keeps the default's skin stiffnesses.
TEST(HeadFit, ALargerCopyKeepsTheSkinStiffness) {
  TriMesh larger = source_skin();
  for (std::size_t i = 0; i < larger.v.size(); ++i) larger.v.set(i, 1.5 * larger.v.get(i));
  const HeadFit f = fit_head(default_spec(), source_skin(), larger, HeadFitOptions{});
  EXPECT_NEAR(f.size_ratio, 1.5, 1e-9);
  EXPECT_NEAR(f.vertex_area_ratio, 1.0, 1e-9);
  const SkinStiffness& k = default_spec().skin;
  EXPECT_NEAR(f.spec.skin.stretch, k.stretch, 1e-9);
  EXPECT_NEAR(f.spec.skin.area, k.area, 1e-9);
  EXPECT_NEAR(f.spec.skin.bending, k.bending, 1e-9);
  EXPECT_NEAR(f.spec.skin.anchor, k.anchor, 1e-9);
}

TEST(HeadFitInput, RefusesMeshesThatCannotBeAFace) {
  TriMesh few;
  for (int i = 0; i < 10; ++i) few.v.push_back(Vec3(i, i % 3, i % 2));
  few.tris = {{0, 1, 2}, {2, 3, 4}};
  EXPECT_THROW(check_head_mesh(few, "few.obj"), InputError);
  try {
    check_head_mesh(few, "few.obj");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("few.obj: expected a face mesh of at least 100"),
              std::string::npos)
        << e.what();
  }
  // A flat 12 × 12 grid: enough vertices, nothing face-like.
  TriMesh flat;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) flat.v.push_back(Vec3(0.01 * x, 0.01 * y, 0));
  for (int y = 0; y + 1 < 12; ++y)
    for (int x = 0; x + 1 < 12; ++x) {
      const int a = y * 12 + x;
      flat.tris.push_back({a, a + 1, a + 13});
      flat.tris.push_back({a, a + 13, a + 12});
    }
  try {
    check_head_mesh(flat, "flat.obj");
    ADD_FAILURE() << "a flat grid was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flat.obj: flat along z"), std::string::npos) << e.what();
  }
}

// A fin: a third triangle on an edge of the default skin. Refused, naming the edge.
TEST(HeadFitInput, RefusesANonManifoldEdge) {
  TriMesh fin = source_skin();
  const Tri t = fin.tris[10];
  fin.v.push_back(fin.v.get(t[0]) + Vec3(0, 0, 0.01));
  fin.tris.push_back({t[0], t[1], static_cast<int>(fin.v.size()) - 1});
  const std::string edge = "the edge between vertices " + std::to_string(std::min(t[0], t[1]) + 1) +
                           " and " + std::to_string(std::max(t[0], t[1]) + 1) +
                           " is shared by 3 faces";
  try {
    check_head_mesh(fin, "fin.obj");
    ADD_FAILURE() << "a non-manifold edge was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fin.obj: non-manifold: " + edge), std::string::npos)
        << e.what();
  }
  check_head_mesh(source_skin(), "default");  // open borders (the mask's edge) are fine
}

// Vertices no face uses (Blender leaves them behind) are left out: a loose vertex exactly
// where a landmark would snap is not chosen, and is listed.
TEST(HeadFitInput, LeavesLooseVerticesOut) {
  const Fitted& f = fitted(1);
  TriMesh target = f.target;
  for (const PlacedLandmark& l : f.fit.landmarks)
    if (l.name == "fdp_9_3" || l.name == "fdp_8_3") target.v.push_back(l.fitted);
  ASSERT_EQ(target.v.size(), f.target.v.size() + 2);
  check_head_mesh(target, "loose.obj");
  const HeadFit fit = fit_head(default_spec(), source_skin(), target, HeadFitOptions{});
  EXPECT_TRUE(fit.problems.empty());
  const int n = static_cast<int>(f.target.v.size());
  EXPECT_EQ(fit.loose_vertices, (std::vector<int>{n, n + 1}));
  for (const LandmarkSpec& l : fit.spec.landmarks)
    for (int v : l.vertices) EXPECT_LT(v, n) << l.name;
  for (const auto& [name, contour] : fit.spec.openings)
    for (int v : contour) EXPECT_LT(v, n) << name;
  EXPECT_EQ(fit.spec.landmarks[0].vertices, f.fit.spec.landmarks[0].vertices);
}

// The refinement reports whether it stopped moving or ran into its round limit.
TEST(HeadFit, ReportsWhetherTheRefinementConverged) {
  const Fitted& f = fitted(0);
  EXPECT_TRUE(f.fit.converged);
  EXPECT_LT(f.fit.iterations, HeadFitOptions{}.max_iterations);
  HeadFitOptions one;
  one.max_iterations = 1;  // the first round always moves (from zero) and adds pairs
  const HeadFit cut = fit_head(default_spec(), source_skin(), f.target, one);
  EXPECT_FALSE(cut.converged);
  EXPECT_EQ(cut.iterations, 1);
}

TEST(HeadFitInput, ReportsAFaceTheWrongWayRound) {
  // The default skin turned to face −z: fits, but the nose is behind the eyes.
  TriMesh back = source_skin();
  for (std::size_t i = 0; i < back.v.size(); ++i) {
    const Vec3 p = back.v.get(i);
    back.v.set(i, Vec3(-p.x(), p.y(), -p.z()));
  }
  const HeadFit f = fit_head(default_spec(), source_skin(), back, HeadFitOptions{});
  ASSERT_FALSE(f.problems.empty());
}

TEST(ClosestPointOnTriangle, RegionsOfTheTriangle) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(closest_point_on_triangle(Vec3(0.2, 0.2, 5), a, b, c).isApprox(Vec3(0.2, 0.2, 0)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(-1, -1, 0), a, b, c).isApprox(a));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(2, -1, 0), a, b, c).isApprox(b));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(0.5, -1, 1), a, b, c).isApprox(Vec3(0.5, 0, 0)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(1, 1, 0), a, b, c).isApprox(Vec3(0.5, 0.5, 0)));
}

}  // namespace
}  // namespace facectl::face
