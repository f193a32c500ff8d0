// Development aid (not a test): how the full face converges, in time and in mesh size.
//   face_convergence_probe random [N] [seed] [vertices]
//     N random inputs, every muscle c ~ U(0, 1), jaw uniform over its envelope: how many
//     reach steady state (SteadyStateOptions defaults), the frames they need, and how far
//     the control points move between frames 300 and 600 of a plain run.
//   face_convergence_probe resolution V1 V2 ...
//     Every library expression at steady state on each skin size: control-point
//     differences between consecutive sizes (RMS, max, and each expression's worst point).
//   face_convergence_probe trace EXPRESSION|cp=C [frames] [stride] [noteeth]
//     One held input (cp=C: corrugator and procerus at C alone): skin and muscle motion
//     every `stride` frames (20).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "facectl/face/steady_state.hpp"

using namespace facectl::face;

namespace {

std::vector<int> control_landmarks(const FaceModel& m) {
  std::vector<int> cps;
  for (const auto& n : m.spec.control_points) cps.push_back(m.landmark_index(n));
  return cps;
}

std::vector<Vec3> displacements(const FaceModel& m, const FaceData& d,
                                const std::vector<int>& cps) {
  std::vector<Vec3> out;
  for (int l : cps)
    out.push_back(1e3 * (landmark_position(m, d.skin_x, l) - landmark_position(m, m.skin.v, l)));
  return out;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

int random_study(int n, unsigned seed, std::size_t vertices) {
  const HeadSpec spec = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  const FaceModel m = build_face_model(spec, vertices);
  const std::vector<int> cps = control_landmarks(m);
  ReduceOptions ro;
  ro.active_probability = 1.0;  // every muscle active, c ~ U(0, 1)
  ro.max_contraction = 1.0;
  FaceData d = make_face_data(m);
  const SteadyStateOptions o;
  std::vector<double> frames, settled_frames, drift_max, residual;
  double drift_sq = 0;
  int converged = 0, drift_n = 0;
  for (const ReducedSample& s : random_samples(spec, ro, n, seed)) {
    FaceInput in;
    in.contractions = s.contractions;
    in.jaw = s.jaw;
    reset_face_data(m, d);
    const SteadyStateResult r = run_to_steady_state(m, d, in, o);
    converged += r.converged;
    std::size_t moving = 0;  // the vertex that moves most in the next 2 frames
    double muscle_motion = 0;
    if (!r.converged) {
      const Points before = d.skin_x, mus = d.muscles;
      step_face(m, d, in);
      step_face(m, d, in);
      for (std::size_t i = 0; i < mus.size(); ++i)
        muscle_motion = std::max(muscle_motion, 1e3 * (d.muscles.get(i) - mus.get(i)).norm());
      double w = 0;
      for (std::size_t i = 0; i < before.size(); ++i)
        if (const double e = (d.skin_x.get(i) - before.get(i)).norm(); e > w) w = e, moving = i;
    }
    frames.push_back(r.converged ? r.frames : o.max_frames + 1.0);
    if (r.converged) settled_frames.push_back(r.frames);
    residual.push_back(r.residual_mm);
    reset_face_data(m, d);
    for (int f = 0; f < 300; ++f) step_face(m, d, in);
    const std::vector<Vec3> a = displacements(m, d, cps);
    for (int f = 300; f < 600; ++f) step_face(m, d, in);
    const std::vector<Vec3> b = displacements(m, d, cps);
    double worst = 0;
    for (std::size_t p = 0; p < a.size(); ++p) {
      const double e = (b[p] - a[p]).norm();
      worst = std::max(worst, e);
      drift_sq += e * e;
      ++drift_n;
    }
    drift_max.push_back(worst);
    if (!r.converged)
      std::printf(
          "unsettled: residual %.3f mm after %d frames, 300→600 drift %.3f mm; vertex %zu at "
          "(%.0f, %.0f, %.0f) mm moves most; muscles %.3f mm\n",
          r.residual_mm, r.frames, worst, moving, 1e3 * m.skin.v.x[moving],
          1e3 * m.skin.v.y[moving], 1e3 * m.skin.v.z[moving], muscle_motion);
  }
  std::printf(
      "%zu vertices, %d inputs (seed %u): %d settled to %.3f mm (window %d) within %d frames\n"
      "frames to settle (unsettled count as %d): median %.0f, p95 %.0f, max %.0f; of the "
      "settled alone: median %.0f, p95 %.0f, max %.0f\n"
      "final residual: median %.4f mm, max %.3f mm\n"
      "control points 300→600 frames: RMS %.4f mm; per input max: median %.4f, p95 %.3f, "
      "max %.3f mm\n",
      m.skin.v.size(), n, seed, converged, o.tolerance_mm, o.window, o.max_frames, o.max_frames + 1,
      percentile(frames, 0.5), percentile(frames, 0.95),
      *std::max_element(frames.begin(), frames.end()), percentile(settled_frames, 0.5),
      percentile(settled_frames, 0.95), percentile(settled_frames, 1.0), percentile(residual, 0.5),
      *std::max_element(residual.begin(), residual.end()),
      std::sqrt(drift_sq / std::max(drift_n, 1)), percentile(drift_max, 0.5),
      percentile(drift_max, 0.95), *std::max_element(drift_max.begin(), drift_max.end()));
  return 0;
}

int resolution_study(const std::vector<std::size_t>& sizes) {
  const HeadSpec spec = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  const ExpressionLibrary lib =
      load_expression_library(FACECTL_CONFIG_DIR "/expressions/library.yaml", spec);
  // result[size][expression][point]
  std::vector<std::vector<std::vector<Vec3>>> res;
  for (std::size_t v : sizes) {
    const FaceModel m = build_face_model(spec, v);
    const std::vector<int> cps = control_landmarks(m);
    FaceData d = make_face_data(m);
    res.emplace_back();
    for (const Expression& e : lib.expressions) {
      reset_face_data(m, d);
      const SteadyStateResult r = run_to_steady_state(m, d, face_input(e), SteadyStateOptions{});
      if (!r.converged)
        std::printf("%zu vertices, %s: unsettled, residual %.3f mm\n", m.skin.v.size(),
                    e.name.c_str(), r.residual_mm);
      res.back().push_back(displacements(m, d, cps));
    }
    std::fprintf(stderr, "%zu vertices done\n", m.skin.v.size());
  }
  for (std::size_t k = 0; k + 1 < sizes.size(); ++k) {
    std::printf("\n%zu vs %zu vertices\n%-17s %8s %8s  %s\n", sizes[k], sizes[k + 1], "expression",
                "RMS mm", "max mm", "worst point");
    double all_sq = 0, all_max = 0;
    int all_n = 0;
    for (std::size_t e = 0; e < lib.expressions.size(); ++e) {
      double sq = 0, worst = 0;
      std::size_t worst_p = 0;
      const auto& a = res[k][e];
      const auto& b = res[k + 1][e];
      for (std::size_t p = 0; p < a.size(); ++p) {
        const double d = (a[p] - b[p]).norm();
        sq += d * d;
        if (d > worst) worst = d, worst_p = p;
      }
      all_sq += sq, all_n += static_cast<int>(a.size()), all_max = std::max(all_max, worst);
      std::printf("%-17s %8.2f %8.2f  %s\n", lib.expressions[e].name.c_str(),
                  std::sqrt(sq / static_cast<double>(a.size())), worst,
                  spec.control_points[worst_p].c_str());
    }
    std::printf("%-17s %8.2f %8.2f\n", "all", std::sqrt(all_sq / all_n), all_max);
  }
  return 0;
}

// One held input: a library expression, or "cp=C" for the corrugator and procerus at C
// alone. Every `stride` frames, the largest skin and muscle particle motion over those frames
// (mm), the skin vertex that moved most, and the frame's teeth contacts.
int trace(const std::string& what, int frames, int stride, bool teeth) {
  const HeadSpec spec = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  const FaceModel m = build_face_model(spec);
  const ExpressionLibrary lib =
      load_expression_library(FACECTL_CONFIG_DIR "/expressions/library.yaml", spec);
  std::vector<double> cs(spec.commanded.size(), 0.0);
  FaceInput in;
  if (what.rfind("cp=", 0) == 0) {
    for (std::size_t k = 0; k < cs.size(); ++k)
      if (spec.commanded[k].rfind("corrugator", 0) == 0 ||
          spec.commanded[k].rfind("procerus", 0) == 0)
        cs[k] = std::atof(what.c_str() + 3);
    in.contractions = cs;
  } else if (const Expression* e = lib.find(what)) {
    in = face_input(*e);
  } else {
    std::fprintf(stderr, "no expression %s\n", what.c_str());
    return 2;
  }
  in.teeth_collision = teeth;
  FaceData d = make_face_data(m);
  auto largest = [](const Points& a, const Points& b, std::size_t& at) {
    double w = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (const double e = (a.get(i) - b.get(i)).norm(); e > w) w = e, at = i;
    return 1e3 * w;
  };
  Points skin = d.skin_x, mus = d.muscles;
  for (int f = 1; f <= frames; ++f) {
    step_face(m, d, in);
    if (f % stride) continue;
    std::size_t si = 0, mi = 0;
    const double ds = largest(d.skin_x, skin, si), dm = largest(d.muscles, mus, mi);
    const Vec3 at = 1e3 * m.skin.v.get(si);
    std::printf(
        "frame %4d: skin %.4f mm (vertex %zu at %.0f %.0f %.0f mm), muscles %.4f mm "
        "(particle %zu), teeth contacts %d\n",
        f, ds, si, at.x(), at.y(), at.z(), dm, mi, d.hits);
    skin = d.skin_x, mus = d.muscles;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "random")
    return random_study(argc > 2 ? std::atoi(argv[2]) : 100,
                        argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1,
                        argc > 4 ? static_cast<std::size_t>(std::atoi(argv[4])) : 0);
  if (mode == "trace" && argc > 2)
    return trace(argv[2], argc > 3 ? std::atoi(argv[3]) : 1000,
                 argc > 4 ? std::max(1, std::atoi(argv[4])) : 20,
                 !(argc > 5 && std::string(argv[5]) == "noteeth"));
  if (mode == "resolution" && argc > 2) {
    std::vector<std::size_t> sizes;
    for (int i = 2; i < argc; ++i) sizes.push_back(static_cast<std::size_t>(std::atoi(argv[i])));
    return resolution_study(sizes);
  }
  std::fprintf(stderr,
               "usage: face_convergence_probe random [N] [seed] [vertices]\n"
               "       face_convergence_probe resolution V1 V2 ...   (0 = the base mesh)\n"
               "       face_convergence_probe trace EXPRESSION|cp=C [frames] [stride] [noteeth]\n");
  return 2;
}
