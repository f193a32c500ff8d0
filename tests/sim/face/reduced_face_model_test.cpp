// The reduced model: allocation-free evaluation, exact save/load, error messages, and a
// fit that tracks the full model on held-out inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "alloc_counter.hpp"
#include "default_head.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "facectl/face/reduced_test_sets.hpp"
#include "tests/support/sample_count.hpp"

namespace facectl::face {
namespace {

const ReducedFaceModel& small_fit(ReduceReport* report = nullptr) {
  static ReduceReport rep;
  static const ReducedFaceModel r = [] {
    // Each sample runs to steady state but for at most 120 frames of four passes (40
    // under the sanitizers, with a quarter of the samples: the fit then runs every path of
    // the full model and the regression, but is too small to meet the accuracy bound
    // below). Not every input of the distribution settles (docs/FACE_MODEL.md, "Known
    // issues").
    using facectl::testing::kSanitized;
    ReduceOptions o;
    o.train_samples = kSanitized ? 40 : 160;
    o.test_samples = kSanitized ? 10 : 40;
    o.steady.max_frames = kSanitized ? 40 : 120;
    return build_reduced_model(testing::default_model(), o, &rep);
  }();
  if (report) *report = rep;
  return r;
}

TEST(ReducedFaceModel, FitTracksTheFullModelOnHeldOutInputs) {
  ReduceReport rep;
  small_fit(&rep);
  // A regression bound for this small, fast fit (160 mixes and 211 one-signal sweeps);
  // the shipped model's measured errors are in docs/FACE_MODEL.md, "Reduced model".
  if (!facectl::testing::kSanitized) {
    // Held out: mixes of the fit's distribution (c up to 1, up to every muscle), on which
    // this fit measured 0.68 mm RMS, 3.5 mm at most (2026-11-29); the shipped fit 0.44 mm,
    // 7.4 mm at most.
    EXPECT_LT(rep.test_rms_mm, 1.5);
    EXPECT_LT(rep.test_max_mm, 20.0);
  }
  EXPECT_TRUE(std::isfinite(rep.test_max_mm));
  EXPECT_GT(rep.test_rms_mm, 0.0);
  RecordProperty("unsettled_runs", rep.unsettled_runs);
  RecordProperty("test_rms_um", static_cast<int>(1e3 * rep.test_rms_mm));
}

const ReducedFaceModel& shipped() {
  static const ReducedFaceModel r =
      load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt", testing::default_spec());
  return r;
}

TEST(ReducedFaceModel, ZeroInputGivesZeroDisplacement) {
  const ReducedFaceModel& r = shipped();
  ReducedFaceWorkspace w = make_reduced_workspace(r);
  std::vector<double> c(r.muscles.size(), 0.0), out(3 * r.control_points.size(), 1.0);
  evaluate(r, w, ReducedInput{c}, out);
  for (double v : out) EXPECT_EQ(v, 0.0);
}

TEST(ReducedFaceModel, EvaluateDoesNotAllocate) {
  const ReducedFaceModel& r = shipped();
  ReducedFaceWorkspace w = make_reduced_workspace(r);
  std::vector<double> c(r.muscles.size(), 0.3), out(3 * r.control_points.size());
  testing::arm_alloc_counter();
  ReducedInput in{c, 0.1, 0.02, 0.003};
  in.eyelid_closure[0] = 0.4;
  in.eyelid_closure[1] = 0.7;
  for (int i = 0; i < 100; ++i) evaluate(r, w, in, out);
  EXPECT_EQ(testing::disarm_alloc_counter(), 0);
}

TEST(ReducedFaceModel, SaveLoadRoundTripIsExact) {
  const ReducedFaceModel& r = shipped();
  const std::string p = (std::filesystem::temp_directory_path() /
                         ("facectl_reduced_" + std::to_string(getpid()) + ".txt"))
                            .string();
  save_reduced_model(r, p);
  const ReducedFaceModel back = load_reduced_model(p, testing::default_spec());
  EXPECT_EQ(back.control_points, r.control_points);
  EXPECT_EQ(back.features, r.features);
  EXPECT_EQ(back.fitted_to, r.fitted_to);
  EXPECT_TRUE(back.coefficients == r.coefficients);
}

TEST(ReducedFaceModel, ShippedCacheMatchesTheHead) {
  EXPECT_EQ(shipped().control_points, testing::default_spec().control_points);
  EXPECT_EQ(shipped().muscles, testing::default_spec().commanded);
}

TEST(ReducedFaceModel, ShippedCacheTracksTheFullModelOnAnExpression) {
  // Joy is not in the training set; its lip corners must agree within 1.5 mm.
  const FaceModel& m = testing::default_model();
  FaceData d = make_face_data(m);
  ReducedSample s;
  s.contractions.assign(m.spec.commanded.size(), 0.0);
  for (std::size_t k = 0; k < s.contractions.size(); ++k)
    if (m.spec.commanded[k].rfind("zygomaticus_major", 0) == 0) s.contractions[k] = 0.5;
  s.jaw.pitch_rad = 0.05;
  const std::vector<int> cps = m.landmark_indices(shipped().control_points);
  const std::vector<double> full = full_model_response(m, d, cps, s, SteadyStateOptions{});
  ReducedFaceWorkspace w = make_reduced_workspace(shipped());
  std::vector<double> out(full.size());
  evaluate(shipped(), w, reduced_input(s), out);
  for (std::size_t p = 0; p < cps.size(); ++p) {
    const Vec3 e(out[3 * p] - full[3 * p], out[3 * p + 1] - full[3 * p + 1],
                 out[3 * p + 2] - full[3 * p + 2]);
    EXPECT_LT(e.norm(), 1.5e-3) << shipped().control_points[p];
  }
}

TEST(ReducedFaceModel, SettledOnlyErrorsLeaveOutTheRunsThatDidNotSettle) {
  // The relaxed face settles within 100 frames; every muscle at 1 with the jaw open does not.
  const FaceModel& m = testing::default_model();
  NamedSampleSet set{"two", "", {}};
  ReducedSample relaxed;
  relaxed.contractions.assign(m.spec.commanded.size(), 0.0);
  ReducedSample busy = relaxed;
  busy.contractions.assign(m.spec.commanded.size(), 1.0);
  busy.jaw.pitch_rad = 0.25;
  set.samples = {relaxed, busy};
  SteadyStateOptions steady;
  steady.max_frames = 100;
  const SetError all = reduced_errors(m, shipped(), {set}, steady).front();
  const SetError settled = reduced_errors(m, shipped(), {set}, steady, true).front();
  EXPECT_EQ(all.unsettled, 1);
  EXPECT_EQ(all.measured, 2);
  EXPECT_EQ(settled.unsettled, 1);
  EXPECT_EQ(settled.measured, 1);
  EXPECT_TRUE(settled.worst.ends_with(" in sample 0")) << settled.worst;
  EXPECT_LT(settled.max_mm, all.max_mm);
}

TEST(ReducedFaceModel, MalformedFileNamesFileAndLine) {
  const std::string p = (std::filesystem::temp_directory_path() /
                         ("facectl_bad_reduced_" + std::to_string(getpid()) + ".txt"))
                            .string();
  std::ofstream(p) << "facectl-reduced-face 4\nfitted_to 1 face.yaml\n";
  try {
    load_reduced_model(p, testing::default_spec());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(p + ":2:"), std::string::npos) << e.what();
  }
}

// A copy of the default head in a fresh folder, with the shipped reduced model.
std::filesystem::path copy_of_default_head(const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("facectl_head_" + tag + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::copy(FACECTL_DEFAULT_HEAD_DIR, dir, fs::copy_options::recursive);
  return dir;
}

std::string load_error(const std::filesystem::path& dir) {
  try {
    load_reduced_model((dir / "reduced_face.txt").string(), load_head_spec(dir.string()));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReducedFaceModel, AModelFittedToOtherHeadFilesIsRefusedAsStale) {
  const auto dir = copy_of_default_head("stale");
  EXPECT_EQ(load_error(dir), "");
  // Any change of bytes counts, even one the parser ignores.
  for (const std::string& file :
       std::vector<std::string>{"skin.obj", "landmarks.yaml", "muscles.yaml", "face.yaml"}) {
    const auto copy = copy_of_default_head("stale_" + std::to_string(file.size()));
    std::ofstream(copy / file, std::ios::app) << "\n# edited\n";
    const std::string e = load_error(copy);
    EXPECT_NE(e.find("reduced_face.txt:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("stale: " + (copy / file).string() + " changed"), std::string::npos) << e;
    EXPECT_NE(e.find("facectl face reduce"), std::string::npos) << e;
    std::filesystem::remove_all(copy);
  }
  std::filesystem::remove_all(dir);
}

TEST(ReducedFaceModel, AnOlderFormatIsRefusedWithTheReason) {
  // Format 1 had no record of its head; 2 took no eyelids; 3 no squared contractions.
  for (int v : {1, 2, 3}) {
    const auto dir = copy_of_default_head("v" + std::to_string(v));
    std::ofstream(dir / "reduced_face.txt")
        << "facectl-reduced-face " << v << "\nfitted_to 0\nmuscles 0\n";
    const std::string e = load_error(dir);
    EXPECT_NE(e.find("reduced_face.txt:1:"), std::string::npos) << e;
    EXPECT_NE(e.find("expected format 4"), std::string::npos) << e;
    EXPECT_NE(e.find("facectl face reduce"), std::string::npos) << e;
    std::filesystem::remove_all(dir);
  }
}

// A file whose features repeat a product (two equal columns) or go beyond degree 4 is
// refused: the fit writes neither, and verify's rounding margin assumes degree 4 at most.
TEST(ReducedFaceModel, RepeatedProductsAndHighDegreesAreRefused) {
  const auto dir = copy_of_default_head("products");
  const HeadSpec spec = load_head_spec(dir.string());
  const std::string file = (dir / "reduced_face.txt").string();
  const ReducedFaceModel shipped = load_reduced_model(file, spec);
  const std::size_t n = shipped.muscles.size();
  const int one = constant_variable(n);
  // A muscle whose c² the model holds ({c, c, 1}).
  const auto c2 = std::find_if(shipped.features.begin(), shipped.features.end(), [&](auto t) {
    return t[0] < static_cast<int>(n) && t[1] == t[0] && t[2] == one;
  });
  ASSERT_NE(c2, shipped.features.end());
  const int c0 = (*c2)[0], sq = square_variable(n, c0);
  for (const auto& [triple, message] :
       {std::pair{std::array{one, one, sq}, "the same product"},  // c² again
        std::pair{std::array{c0, sq, sq}, "has degree 5"}}) {
    ReducedFaceModel m = shipped;
    m.features.back() = triple;
    save_reduced_model(m, file);
    try {
      load_reduced_model(file, spec);
      ADD_FAILURE() << "accepted " << message;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace facectl::face
