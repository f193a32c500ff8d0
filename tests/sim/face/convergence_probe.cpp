// Development aid (not a test): how the full face converges, in time and in mesh size.
//   face_convergence_probe random [N] [seed] [vertices]
//     N random inputs, every muscle c ~ U(0, 1), jaw uniform over its envelope: how many
//     reach steady state (SteadyStateOptions defaults), the frames they need, and how far
//     the control points move between frames 300 and 600 of a plain run.
//   face_convergence_probe resolution V1 V2 ...
//     Every library expression at steady state on each skin size: control-point
//     differences between consecutive sizes (RMS, max, and each expression's worst point).
//   face_convergence_probe depth MM1 MM2 ...
//     The same across the offset skull's soft-tissue depths (face.yaml's 8 mm), base mesh.
//   face_convergence_probe trace EXPRESSION|cp=C [frames] [stride] [noteeth]
//     One held input (cp=C: corrugator and procerus at C alone): skin and muscle motion
//     every `stride` frames (20).
//   face_convergence_probe muscles [N] [seed] [frames]
//     The random study's inputs on the muscles alone: which still move after `frames`.
//   face_convergence_probe mdetail [N] [seed] [frames]
//     The same, muscle by muscle: period-2 cycles and steady creep told apart.
//   face_convergence_probe single [C]
//     Each muscle alone at C (1), the jaw at rest: which settle, and what still moves.
//   face_convergence_probe passes SKIN MUSCLE
//     Every library expression at steady state under the head's solver and under SKIN skin
//     iterations and MUSCLE muscle passes a frame: frames to settle, control-point differences.
//   face_convergence_probe sensitivity [N] [seed] [eps]
//     N dense inputs run to steady state at c and at c + eps (0.001): how far a small
//     change of input moves the control points and the muscles (jumps between steady states).
//   face_convergence_probe dump OUT.csv [samples] [shard] [shards]
//     `face reduce`'s training inputs and check-reduced's sets with the full model's steady
//     states, as CSV: a cache for trying forms of the reduced model offline.
//   face_convergence_probe muscle HEADDIR EXPRESSION MUSCLE
//     One muscle of a head folder, its particles at rest and at the expression's steady state.
//   face_convergence_probe mirror HEADDIR
//     Each muscle's rest particles against its mirror partner's reflected in x = 0.
//   face_convergence_probe skin HEADDIR EXPRESSION [frames]
//     After a run to steady state, the skin vertices that still move over `frames` (6),
//     and which muscle each vertex rides on (FACE_CORNERS=R: near the mouth corners;
//     FACE_NEAR=LANDMARK:R near another landmark); FACE_POINTS=A,B prints those landmarks'
//     displacements. FACE_LIBRARY=FILE replaces the shipped library in every mode.
//   face_convergence_probe fixed [N] [seed] [passes] [tolerance_mm]
//     Whether `passes`-pass steady states of dense inputs are the head solver's: how far its
//     frames take them, and where it settles; where they alternate, which vertex and anchor.
// Study knobs from the environment, for every mode: FACE_STRETCH, FACE_BENDING, FACE_AREA,
// FACE_ANCHOR, FACE_DAMPING, FACE_MINAREA override the head's skin values, FACE_MVOLUME,
// FACE_MBEND, FACE_MPOSITION its muscles' (sheet and sphincter alike); FACE_SCALE=
// stretch|area|density|local scales them with the skin size or vertex area (see
// study_head_for and study_model); in the random study
// FACE_FREEZE=N freezes the muscles after N frames, FACE_NOTEETH=1 drops the contacts and
// FACE_PASSES=N runs N skin iterations and muscle passes a frame; in the resolution study
// FACE_GLOBAL=G multiplies every skin stiffness by G, and FACE_TOL / FACE_MAXFRAMES set
// the steady state's tolerance and frame limit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "facectl/face/reduced_test_sets.hpp"
#include "facectl/face/skin_density.hpp"
#include "facectl/face/steady_state.hpp"

using namespace facectl::face;

namespace {

std::vector<int> control_landmarks(const FaceModel& m) {
  return m.landmark_indices(m.spec.control_points);
}

// The largest distance between points of the same index in two equal-sized sets, in mm,
// and at which index.
double largest(const Points& a, const Points& b, std::size_t& at) {
  double w = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (const double e = (a.get(i) - b.get(i)).norm(); e > w) w = e, at = i;
  return 1e3 * w;
}

// The muscle whose particles carry anchor j's support, or -1 (the skull).
int anchor_muscle(const FaceModel& m, std::size_t j) {
  const SurfacePoint& sp = m.anchor_support[j];
  if (sp.layer != Layer::kMuscle) return -1;
  for (std::size_t k = 0; k < m.muscles.size(); ++k)
    if (sp.i0 >= m.muscles[k].first && sp.i0 < m.muscles[k].first + m.muscles[k].particle_count())
      return static_cast<int>(k);
  return -1;
}

// What skin vertex v's anchor rests on (anchor v: one per vertex, in order): a muscle's
// name, or "skull" (the jaw included).
std::string anchor_support_name(const FaceModel& m, std::size_t v) {
  const int k = anchor_muscle(m, v);
  return k < 0 ? "skull" : m.muscles[static_cast<std::size_t>(k)].name;
}

std::vector<Vec3> displacements(const FaceModel& m, const FaceData& d,
                                const std::vector<int>& cps) {
  std::vector<Vec3> out;
  for (int l : cps)
    out.push_back(1e3 * (landmark_position(m, d.skin_x, l) - landmark_position(m, m.skin.v, l)));
  return out;
}

// Study overrides of the head's skin stiffnesses from the environment (FACE_STRETCH,
// FACE_BENDING, FACE_AREA, FACE_ANCHOR, FACE_DAMPING, FACE_MINAREA), for every mode.
HeadSpec study_head() {
  HeadSpec spec = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  const std::pair<const char*, double*> knobs[] = {
      {"FACE_STRETCH", &spec.skin.stretch}, {"FACE_BENDING", &spec.skin.bending},
      {"FACE_AREA", &spec.skin.area},       {"FACE_ANCHOR", &spec.skin.anchor},
      {"FACE_DAMPING", &spec.skin.damping}, {"FACE_MINAREA", &spec.skin.min_projected_area}};
  // Muscle knobs, the same value for sheets and sphincters.
  for (const auto& [name, member] : {std::pair{"FACE_MVOLUME", &MuscleStiffness::volume},
                                     std::pair{"FACE_MBEND", &MuscleStiffness::bend},
                                     std::pair{"FACE_MPOSITION", &MuscleStiffness::position}})
    if (const char* e = std::getenv(name)) {
      spec.sheet.*member = spec.sphincter.*member = std::atof(e);
      std::fprintf(stderr, "%s = %g\n", name, std::atof(e));
    }
  for (const auto& [name, value] : knobs)
    if (const char* e = std::getenv(name)) {
      *value = std::atof(e);
      std::fprintf(stderr, "%s = %g\n", name, *value);
    }
  return spec;
}

// The default head's base skin size, the reference of the FACE_SCALE variants below.
constexpr double kBaseVertices = 468;

// The skin's stiffnesses for a variant of `vertices` (0: the base mesh). FACE_SCALE=stretch:
// the skin stretch scaled by n/n_base (at most 1), the per-edge stiffness that keeps the
// edge network's stiffness per unit area. FACE_SCALE=density (and local, with study_model's
// anchors): the fitted heads' rule (skin_density.hpp) with ratio n_base/n; the builder's
// own anchor scaling supplies one factor of the anchors' ratio².
HeadSpec study_head_for(std::size_t vertices) {
  HeadSpec spec = study_head();
  const char* e = std::getenv("FACE_SCALE");
  // FACE_GLOBAL=G: every per-element skin stiffness times G (the same weights, smaller
  // steps: how far Gauss–Seidel's order moves the fixed point).
  if (const char* g = std::getenv("FACE_GLOBAL")) {
    const double f = std::atof(g);
    for (double* v : {&spec.skin.stretch, &spec.skin.area, &spec.skin.bending, &spec.skin.anchor})
      *v *= f;
    std::fprintf(stderr, "FACE_GLOBAL = %g\n", f);
  }
  if (e && vertices > 0 && (std::string(e) == "density" || std::string(e) == "local")) {
    const double r = kBaseVertices / static_cast<double>(vertices);
    spec.skin = stiffness_for_vertex_area(spec.skin, r);
    spec.skin.anchor /= r;
    std::fprintf(
        stderr, "%zu vertices: stretch %g area %g bending %g anchor %g (x%g in the builder)\n",
        vertices, spec.skin.stretch, spec.skin.area, spec.skin.bending, spec.skin.anchor, r);
    return spec;
  }
  if (!e || vertices == 0 || std::string(e) != "stretch") return spec;
  spec.skin.stretch =
      std::min(1.0, spec.skin.stretch * static_cast<double>(vertices) / kBaseVertices);
  std::fprintf(stderr, "%zu vertices: stretch %g\n", vertices, spec.skin.stretch);
  return spec;
}

// FACE_SCALE=area: each anchor's stiffness in proportion to its own vertex's share of the
// skin area (a third of its triangles'), k_i = anchor·A_i/(A/n_base), at most 1: the mean
// per unit area is kept, the dense lips and eyes get weaker anchors than the sparse cheeks.
FaceModel study_model(std::size_t vertices) {
  const HeadSpec spec = study_head_for(vertices);
  FaceModel m = build_face_model(spec, vertices);
  const char* e = std::getenv("FACE_SCALE");
  // FACE_SCALE=local: density's stretch, area and bending, and area's anchors.
  if (!e || (std::string(e) != "area" && std::string(e) != "local")) return m;
  std::vector<double> area(m.skin.v.size(), 0.0);
  double total = 0;
  for (const Tri& t : m.skin.tris) {
    const double a = 0.5 * (m.skin.v.get(t[1]) - m.skin.v.get(t[0]))
                               .cross(m.skin.v.get(t[2]) - m.skin.v.get(t[0]))
                               .norm();
    for (int v : t) area[v] += a / 3;
    total += a;
  }
  double lo = 1, hi = 0;
  for (std::size_t j = 0; j < m.anchors.size(); ++j) {
    const double k =
        std::min(1.0, spec.skin.anchor * area[m.anchors.particle[j]] / (total / kBaseVertices));
    m.anchors.k[j] = k, lo = std::min(lo, k), hi = std::max(hi, k);
  }
  std::fprintf(stderr, "%zu vertices: anchors per area, k %.3f to %.3f\n", m.skin.v.size(), lo, hi);
  return m;
}

// FACE_PASSES=N: N skin iterations and muscle passes a frame in the random study's runs
// to steady state (SolverPasses).
SteadyStateOptions study_steady() {
  SteadyStateOptions o;
  if (const char* e = std::getenv("FACE_PASSES")) {
    o.passes = {.skin = std::atoi(e), .muscle = std::atoi(e)};
    std::fprintf(stderr, "FACE_PASSES = %d\n", std::atoi(e));
  }
  return o;
}

// The expression library: FACE_LIBRARY=FILE, else the shipped one.
std::string library_path() {
  const char* e = std::getenv("FACE_LIBRARY");
  return e ? e : FACECTL_CONFIG_DIR "/expressions/library.yaml";
}

// FACE_TOL=MM and FACE_MAXFRAMES=N: the resolution study's steady-state tolerance and
// frame limit (SteadyStateOptions defaults otherwise).
SteadyStateOptions study_settle() {
  SteadyStateOptions o;
  if (const char* e = std::getenv("FACE_TOL")) o.tolerance_mm = std::atof(e);
  if (const char* e = std::getenv("FACE_MAXFRAMES")) o.max_frames = std::atoi(e);
  return o;
}

// FACE_NOTEETH=1 turns the teeth contacts off in the random study.
bool study_teeth() {
  return std::getenv("FACE_NOTEETH") == nullptr;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

// Skin bending pairs turned by more than 90° and more than 154° (cos < −0.9) from their
// rest dihedral, and the largest edge strain l/L − 1 of the interior edges.
struct FoldCount {
  int over90 = 0, near_wrap = 0;
  double strain = 0;
};
FoldCount folds(const FaceModel& m, const Points& p) {
  FoldCount f;
  const BendingConstraints& b = m.skin_bending;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const Vec3 pa = p.get(b.a[i]), e = p.get(b.b[i]) - pa, u = p.get(b.c[i]) - pa,
               v = p.get(b.d[i]) - pa;
    const Vec3 n1 = e.cross(u), n2 = e.cross(v);
    const double r = 1 / (n1.norm() * n2.norm());
    const double c = n1.dot(n2) * r, sn = -u.dot(n2) * e.norm() * r;
    const double cd = c * b.cos_rest[i] + sn * b.sin_rest[i];
    f.over90 += cd < 0;
    f.near_wrap += cd < -0.9;
    const double rest = (m.skin.v.get(b.b[i]) - m.skin.v.get(b.a[i])).norm();
    f.strain = std::max(f.strain, e.norm() / rest - 1);
  }
  return f;
}

// run_to_steady_state's criterion with the muscles frozen after `freeze` frames (their
// state is put back before every later step, so each step's muscle passes start from the
// same state): whether the skin settles on still supports.
SteadyStateResult run_frozen(const FaceModel& m, FaceData& d, const FaceInput& in,
                             const SteadyStateOptions& o, int freeze) {
  for (int f = 0; f < freeze; ++f) step_face(m, d, in, o.passes);
  const Points still = d.muscles;
  std::vector<Points> ring;
  SteadyStateResult r;
  for (r.frames = 1; r.frames <= o.max_frames; ++r.frames) {
    d.muscles = still;
    step_face(m, d, in, o.passes);
    if (static_cast<int>(ring.size()) == o.window) ring.erase(ring.begin());
    r.residual_mm = 0;
    for (const Points& h : ring)
      for (std::size_t i = 0; i < h.size(); ++i)
        r.residual_mm = std::max(r.residual_mm, 1e3 * (h.get(i) - d.skin_x.get(i)).norm());
    ring.push_back(d.skin_x);
    if (r.frames >= std::max(o.min_frames, o.window) && r.residual_mm < o.tolerance_mm) {
      r.converged = true;
      break;
    }
  }
  r.frames = std::min(r.frames, o.max_frames);
  return r;
}

int random_study(int n, unsigned seed, std::size_t vertices) {
  const HeadSpec spec = study_head_for(vertices);
  const FaceModel m = study_model(vertices);
  const std::vector<int> cps = control_landmarks(m);
  ReduceOptions ro;
  ro.active_probability = 1.0;  // every muscle active, c ~ U(0, 1)
  ro.max_contraction = 1.0;
  FaceData d = make_face_data(m);
  const SteadyStateOptions o = study_steady();
  std::vector<double> frames, settled_frames, drift_max, residual;
  double drift_sq = 0;
  // FACE_FREEZE=N: the muscles are frozen after N frames (run_frozen).
  const int freeze = std::getenv("FACE_FREEZE") ? std::atoi(std::getenv("FACE_FREEZE")) : 0;
  int converged = 0, drift_n = 0, muscles_moving = 0;
  for (const ReducedSample& s : random_samples(spec, ro, n, seed)) {
    FaceInput in;
    in.contractions = s.contractions;
    in.jaw = s.jaw;
    in.teeth_collision = study_teeth();
    reset_face_data(m, d);
    const SteadyStateResult r =
        freeze > 0 ? run_frozen(m, d, in, o, freeze) : run_to_steady_state(m, d, in, o);
    converged += r.converged;
    const FoldCount fc = folds(m, d.skin_x);
    std::size_t moving = 0;  // the vertex that moves most in the next 2 frames
    double muscle_motion = 0, one_frame = 0;
    if (!r.converged) {
      const Points before = d.skin_x, mus = d.muscles;
      std::size_t at = 0;
      step_face(m, d, in, o.passes);
      one_frame = largest(d.skin_x, before, at);
      step_face(m, d, in, o.passes);
      muscle_motion = largest(d.muscles, mus, at);
      largest(d.skin_x, before, moving);
      muscles_moving += freeze == 0 && muscle_motion > 0.01;
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
    std::printf("folds: %s, pairs over 90° %d, over 154° %d, max strain %.2f\n",
                r.converged ? "settled" : "unsettled", fc.over90, fc.near_wrap, fc.strain);
    if (!r.converged)
      std::printf(
          "unsettled: residual %.3f mm after %d frames, 300→600 drift %.3f mm; vertex %zu at "
          "(%.0f, %.0f, %.0f) mm moves most (%.3f mm in 1 frame); muscles %.3f mm\n",
          r.residual_mm, r.frames, worst, moving, 1e3 * m.skin.v.x[moving],
          1e3 * m.skin.v.y[moving], 1e3 * m.skin.v.z[moving], one_frame, muscle_motion);
  }
  std::printf(
      "%zu vertices, %d inputs (seed %u): %d settled to %.3f mm (window %d) within %d frames\n"
      "frames to settle (unsettled count as %d): median %.0f, p95 %.0f, max %.0f; of the "
      "settled alone: median %.0f, p95 %.0f, max %.0f\n"
      "final residual: median %.4f mm, max %.3f mm; unsettled with muscles moving > 0.01 mm "
      "in 2 frames: %d\n"
      "control points 300→600 frames: RMS %.4f mm; per input max: median %.4f, p95 %.3f, "
      "max %.3f mm\n",
      m.skin.v.size(), n, seed, converged, o.tolerance_mm, o.window, o.max_frames, o.max_frames + 1,
      percentile(frames, 0.5), percentile(frames, 0.95),
      *std::max_element(frames.begin(), frames.end()), percentile(settled_frames, 0.5),
      percentile(settled_frames, 0.95), percentile(settled_frames, 1.0), percentile(residual, 0.5),
      *std::max_element(residual.begin(), residual.end()), muscles_moving,
      std::sqrt(drift_sq / std::max(drift_n, 1)), percentile(drift_max, 0.5),
      percentile(drift_max, 0.95), *std::max_element(drift_max.begin(), drift_max.end()));
  return 0;
}

// The muscles alone (step_skull_and_muscles) run from rest for `frames` frames: their
// last 21 states, oldest first.
std::vector<Points> muscle_history(const FaceModel& m, FaceData& d, const FaceInput& in,
                                   int frames) {
  reset_face_data(m, d);
  std::vector<Points> hist;
  for (int f = 0; f < frames; ++f) {
    step_skull_and_muscles(m, d, in);
    if (f >= frames - 21) hist.push_back(d.muscles);
  }
  return hist;
}

// The muscles alone (step_skull_and_muscles) under the random study's inputs: their
// residual after `frames` frames (largest particle motion over the last 20 frames), and the
// muscle that moves most with its contraction.
int muscle_study(int n, unsigned seed, int frames) {
  const HeadSpec spec = study_head();
  const FaceModel m = build_face_model(spec);
  ReduceOptions ro;
  ro.active_probability = 1.0;
  ro.max_contraction = 1.0;
  FaceData d = make_face_data(m);
  int still = 0;
  std::vector<double> res;
  for (const ReducedSample& s : random_samples(spec, ro, n, seed)) {
    FaceInput in;
    in.contractions = s.contractions;
    in.jaw = s.jaw;
    const std::vector<Points> hist = muscle_history(m, d, in, frames);
    double worst = 0;
    std::size_t at = 0;
    for (const Points& h : hist)
      for (std::size_t i = 0; i < h.size(); ++i)
        if (const double e = 1e3 * (h.get(i) - d.muscles.get(i)).norm(); e > worst)
          worst = e, at = i;
    std::size_t k = 0;
    while (k + 1 < m.muscles.size() && m.muscles[k + 1].first <= static_cast<int>(at)) ++k;
    res.push_back(worst);
    still += worst < 0.01;
    const Points& prev = hist[hist.size() - 2];
    const double last = 1e3 * (prev.get(at) - d.muscles.get(at)).norm();
    const double span = 1e3 * (hist.front().get(at) - d.muscles.get(at)).norm();
    if (worst >= 0.01)
      std::printf(
          "moving: %.3f mm (last frame %.3f, over 20 frames %.3f), %s particle %zu (c = %.2f)\n",
          worst, last, span, m.muscles[k].name.c_str(), at - m.muscles[k].first, d.contraction[k]);
  }
  std::printf(
      "muscles alone after %d frames: %d of %d still to 0.01 mm over 20 frames; residual "
      "median %.4f, max %.3f mm\n",
      frames, still, n, percentile(res, 0.5), *std::max_element(res.begin(), res.end()));
  return 0;
}

// The muscles-alone study muscle by muscle: each moving muscle's largest particle motion
// over the last 1, 2 and 20 frames (r1, r2, r20) and its volume over its rest volume. A
// period-2 cycle shows r2 ≈ 0 < r1; a steady creep r20 ≈ 20·r1. Knobs: MVOLK and MATTACH
// override the volume and attachment stiffness of every muscle, MCLAMP=C caps every
// contraction at C.
int muscle_detail(int n, unsigned seed, int frames) {
  const HeadSpec spec = study_head();
  FaceModel m = build_face_model(spec);
  for (Muscle& mu : m.muscles) {
    if (const char* e = std::getenv("MVOLK")) mu.volume.k = std::atof(e);
    if (const char* e = std::getenv("MATTACH"))
      for (double& k : mu.attach.k) k = std::atof(e);
  }
  ReduceOptions ro;
  ro.active_probability = 1.0;
  ro.max_contraction = 1.0;
  FaceData d = make_face_data(m);
  int still = 0, idx = 0, period2 = 0, creep = 0;
  std::vector<double> res;
  for (const ReducedSample& s : random_samples(spec, ro, n, seed)) {
    FaceInput in;
    std::vector<double> cs = s.contractions;
    if (const char* e = std::getenv("MCLAMP"))
      for (double& c : cs) c = std::min(c, std::atof(e));
    in.contractions = cs;
    in.jaw = s.jaw;
    const std::vector<Points> hist = muscle_history(m, d, in, frames);
    double all = 0;
    for (std::size_t k = 0; k < m.muscles.size(); ++k) {
      const Muscle& mu = m.muscles[k];
      double r1 = 0, r2 = 0, r20 = 0;
      const Points& x = d.muscles;
      for (int i = mu.first; i < mu.first + mu.particle_count(); ++i) {
        r1 = std::max(r1, 1e3 * (x.get(i) - hist[hist.size() - 2].get(i)).norm());
        r2 = std::max(r2, 1e3 * (x.get(i) - hist[hist.size() - 3].get(i)).norm());
        for (const Points& h : hist) r20 = std::max(r20, 1e3 * (x.get(i) - h.get(i)).norm());
      }
      all = std::max(all, r20);
      if (r20 < 0.01) continue;
      const bool p2 = r2<0.05 * r1, cr = r20> 15 * r1;
      period2 += p2, creep += cr;
      std::printf("input %d %-40s c=%.2f r1 %.4f r2 %.4f r20 %.4f vol %.3f%s\n", idx,
                  mu.name.c_str(), d.contraction[k], r1, r2, r20,
                  volume_of(mu.volume, x) / mu.volume.rest,
                  p2   ? " period 2"
                  : cr ? " creep"
                       : "");
    }
    res.push_back(all);
    still += all < 0.01;
    ++idx;
  }
  std::printf(
      "muscles alone after %d frames: %d of %d still; moving muscles in period-2 cycles %d, "
      "creeping %d; residual median %.4f max %.3f mm\n",
      frames, still, n, period2, creep, percentile(res, 0.5),
      *std::max_element(res.begin(), res.end()));
  return 0;
}

// Each commanded muscle alone at c, the jaw at rest, run to steady state (FACE_PASSES
// applies): settled or not, and for those that are not, the skin vertex and the muscle
// particle that move most over the next 20 frames.
int single_study(double c) {
  const HeadSpec spec = study_head();
  const FaceModel m = build_face_model(spec);
  const SteadyStateOptions o = study_steady();
  FaceData d = make_face_data(m);
  int settled = 0;
  for (std::size_t i = 0; i < spec.commanded.size(); ++i) {
    std::vector<double> cs(spec.commanded.size(), 0.0);
    cs[i] = c;
    FaceInput in;
    in.contractions = cs;
    reset_face_data(m, d);
    const SteadyStateResult r = run_to_steady_state(m, d, in, o);
    settled += r.converged;
    const Points skin = d.skin_x, mus = d.muscles;
    for (int f = 0; f < 20; ++f) step_face(m, d, in, o.passes);
    double sk = 0, mu = 0;
    std::size_t v = 0;
    for (std::size_t k = 0; k < skin.size(); ++k)
      if (const double e = 1e3 * (d.skin_x.get(k) - skin.get(k)).norm(); e > sk) sk = e, v = k;
    for (std::size_t k = 0; k < mus.size(); ++k)
      mu = std::max(mu, 1e3 * (d.muscles.get(k) - mus.get(k)).norm());
    const Vec3 at = 1e3 * skin.get(v);
    std::printf(
        "%-28s %s after %4d frames, residual %.3f mm; next 20 frames: skin %.3f mm "
        "(vertex %zu at %.0f, %.0f, %.0f mm), muscles %.3f mm\n",
        spec.commanded[i].c_str(), r.converged ? "settled  " : "UNSETTLED", r.frames, r.residual_mm,
        sk, v, at.x(), at.y(), at.z(), mu);
  }
  std::printf("%d of %zu muscles alone at %.2f settle\n", settled, spec.commanded.size(), c);
  return 0;
}

// The library's settled control points under two solvers: the head's, and `skin` skin
// iterations with `muscle` muscle passes a frame (the same fixed points if both settle).
int passes_study(int skin, int muscle) {
  const HeadSpec base = study_head();
  const ExpressionLibrary lib = load_expression_library(library_path(), base);
  std::vector<std::vector<Vec3>> res[2];
  const FaceModel m = build_face_model(base, 0);
  for (int k = 0; k < 2; ++k) {
    SteadyStateOptions o;
    if (k == 1) o.passes = {.skin = skin, .muscle = muscle};
    const std::vector<int> cps = control_landmarks(m);
    FaceData d = make_face_data(m);
    for (const Expression& e : lib.expressions) {
      reset_face_data(m, d);
      const SteadyStateResult r = run_to_steady_state(m, d, face_input(e), o);
      std::printf("solver %d, %s: %s after %d frames, residual %.3f mm\n", k, e.name.c_str(),
                  r.converged ? "settled" : "unsettled", r.frames, r.residual_mm);
      res[k].push_back(displacements(m, d, cps));
    }
  }
  double all_sq = 0, all_max = 0;
  int all_n = 0;
  for (std::size_t e = 0; e < lib.expressions.size(); ++e) {
    double sq = 0, worst = 0;
    for (std::size_t p = 0; p < res[0][e].size(); ++p) {
      const double d = (res[0][e][p] - res[1][e][p]).norm();  // mm
      sq += d * d, worst = std::max(worst, d);
    }
    all_sq += sq, all_n += static_cast<int>(res[0][e].size()), all_max = std::max(all_max, worst);
    std::printf("%-17s RMS %.3f max %.3f mm\n", lib.expressions[e].name.c_str(),
                std::sqrt(sq / static_cast<double>(res[0][e].size())), worst);
  }
  std::printf("all RMS %.3f max %.3f mm\n", std::sqrt(all_sq / all_n), all_max);
  return 0;
}

// Every library expression at steady state on each model build(k), k < labels.size():
// control-point differences between consecutive models (RMS, max, and each expression's
// worst point). The displacements are from each model's own rest.
int library_study(const std::vector<std::string>& labels,
                  const std::function<FaceModel(std::size_t)>& build) {
  const HeadSpec spec = study_head();
  const ExpressionLibrary lib = load_expression_library(library_path(), spec);
  // result[model][expression][point]
  std::vector<std::vector<std::vector<Vec3>>> res;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    const FaceModel m = build(k);
    const std::vector<int> cps = control_landmarks(m);
    FaceData d = make_face_data(m);
    long frames_used = 0;
    res.emplace_back();
    for (const Expression& e : lib.expressions) {
      reset_face_data(m, d);
      const SteadyStateResult r = run_to_steady_state(m, d, face_input(e), study_settle());
      frames_used += r.frames;
      if (!r.converged)
        std::printf("%s, %s: unsettled, residual %.3f mm\n", labels[k].c_str(), e.name.c_str(),
                    r.residual_mm);
      res.back().push_back(displacements(m, d, cps));
    }
    std::fprintf(stderr, "%s done, %ld frames\n", labels[k].c_str(), frames_used);
  }
  for (std::size_t k = 0; k + 1 < labels.size(); ++k) {
    std::printf("\n%s vs %s\n%-17s %8s %8s  %s\n", labels[k].c_str(), labels[k + 1].c_str(),
                "expression", "RMS mm", "max mm", "worst point");
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

int resolution_study(const std::vector<std::size_t>& sizes) {
  std::vector<std::string> labels;
  for (std::size_t v : sizes) labels.push_back(std::to_string(v) + " vertices");
  return library_study(labels, [&](std::size_t k) { return study_model(sizes[k]); });
}

// The same across soft-tissue depths (the offset skull's one parameter; the muscles rest on
// the skull, so they move with it), on the base mesh.
int depth_study(const std::vector<double>& depths_mm) {
  std::vector<std::string> labels;
  for (double d : depths_mm) {
    char label[48];
    std::snprintf(label, sizeof label, "%g mm tissue", d);
    labels.emplace_back(label);
  }
  return library_study(labels, [&](std::size_t k) {
    HeadSpec spec = study_head();
    spec.tissue_depth = depths_mm[k] * 1e-3;
    return build_face_model(spec);
  });
}

// One held input: a library expression, or "cp=C" for the corrugator and procerus at C
// alone. Every `stride` frames, the largest skin and muscle particle motion over those frames
// (mm), the skin vertex that moved most, and the frame's teeth contacts.
int trace(const std::string& what, int frames, int stride, bool teeth) {
  const HeadSpec spec = study_head();
  const FaceModel m = build_face_model(spec);
  const ExpressionLibrary lib = load_expression_library(library_path(), spec);
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

// How smooth the steady state is in its inputs: N dense inputs (every muscle c ~ U(0, 1),
// jaw uniform), each run to steady state (four passes, as the fit) at c and at c + eps
// (every contraction, clamped to 1). Per input the control points' largest difference and
// the point it is at; a smooth response differs by about eps times its slope.
int sensitivity(int n, unsigned seed, double eps) {
  const HeadSpec spec = study_head();
  const FaceModel m = build_face_model(spec);
  const std::vector<int> cps = control_landmarks(m);
  ReduceOptions ro;
  ro.active_probability = 1.0;
  ro.max_contraction = 1.0;
  FaceData d = make_face_data(m);
  std::vector<double> worst;
  for (const ReducedSample& s : random_samples(spec, ro, n, seed)) {
    ReducedSample t = s;
    for (double& c : t.contractions) c = std::min(1.0, c + eps);
    auto run = [&](const ReducedSample& x, SteadyStateResult& r) {
      std::vector<double> y = full_model_response(m, d, cps, x, ro.steady, &r, study_teeth());
      for (double& v : y) v *= 1e3;  // mm
      return y;
    };
    SteadyStateResult ra, rb;
    const std::vector<double> a = run(s, ra);
    const Points muscles_a = d.muscles;
    const std::vector<double> b = run(t, rb);
    double mw = 0;  // the muscles' largest difference, and whose
    std::string which;
    for (const Muscle& mu : m.muscles)
      for (int k = mu.first; k < mu.first + mu.particle_count(); ++k)
        if (const double e = 1e3 * (d.muscles.get(k) - muscles_a.get(k)).norm(); e > mw)
          mw = e, which = mu.name;
    double w = 0;
    std::size_t at = 0;
    for (std::size_t p = 0; p < cps.size(); ++p)
      if (const double e =
              Vec3(a[3 * p] - b[3 * p], a[3 * p + 1] - b[3 * p + 1], a[3 * p + 2] - b[3 * p + 2])
                  .norm();
          e > w)
        w = e, at = p;
    worst.push_back(w);
    std::printf(
        "%s/%s  largest difference %.3f mm at %s (%.2f, %.2f, %.2f), muscles %.3f mm (%s)\n",
        ra.converged ? "settled" : "UNSETTLED", rb.converged ? "settled" : "UNSETTLED", w,
        spec.control_points[at].c_str(), b[3 * at] - a[3 * at], b[3 * at + 1] - a[3 * at + 1],
        b[3 * at + 2] - a[3 * at + 2], mw, which.c_str());
  }
  std::printf("median %.3f mm, 90th percentile %.3f mm, max %.3f mm\n", percentile(worst, 0.5),
              percentile(worst, 0.9), percentile(worst, 1.0));
  return 0;
}

// The full model's steady-state responses on `face reduce`'s inputs (its training samples,
// seed 1, and check-reduced's named sets, seed 1) as CSV rows: set, index, settled,
// residual_mm, the inputs (contractions, pitch, yaw in rad, protrusion in m, lids) and the
// control points' displacements (x, y, z in m each). Rows k with k % shards == shard, so
// shards can run side by side; a cache for trying forms of the reduced model offline.
int dump(const std::string& path, int samples, int shard, int shards) {
  const HeadSpec spec = study_head();
  const FaceModel m = build_face_model(spec);
  const ExpressionLibrary lib = load_expression_library(library_path(), spec);
  const std::vector<int> cps = control_landmarks(m);
  const ReduceOptions ro;
  std::vector<NamedSampleSet> sets = {
      {"train", "", training_samples(spec, samples, ro.seed, true)}};
  for (NamedSampleSet& s : reduced_test_sets(spec, lib, 200, 1)) sets.push_back(std::move(s));
  FILE* out = std::fopen(path.c_str(), "w");
  if (!out) {
    std::perror(path.c_str());
    return 1;
  }
  FaceData d = make_face_data(m);
  int row = 0;
  for (const NamedSampleSet& set : sets)
    for (std::size_t k = 0; k < set.samples.size(); ++k, ++row) {
      if (row % shards != shard) continue;
      const ReducedSample& s = set.samples[k];
      SteadyStateResult r;
      const std::vector<double> y = full_model_response(m, d, cps, s, ro.steady, &r);
      std::fprintf(out, "%s,%zu,%d,%.4f", set.name.c_str(), k, r.converged ? 1 : 0, r.residual_mm);
      for (double c : s.contractions) std::fprintf(out, ",%.17g", c);
      for (double v : {s.jaw.pitch_rad, s.jaw.yaw_rad, s.jaw.protrusion_m, s.eyelid_closure[0],
                       s.eyelid_closure[1]})
        std::fprintf(out, ",%.17g", v);
      for (double v : y) std::fprintf(out, ",%.17g", v);
      std::fprintf(out, "\n");
      std::fflush(out);
    }
  std::fclose(out);
  return 0;
}

// From rest to the steady state of library expression `expr` (3000 frames at most),
// printing how it went; nullptr (and a message) when the library has no such expression.
const Expression* settle_on(const FaceModel& m, const ExpressionLibrary& lib, const char* expr,
                            FaceData& d) {
  const Expression* e = lib.find(expr);
  if (e == nullptr) {
    std::fprintf(stderr, "no expression '%s' in the library\n", expr);
    return nullptr;
  }
  reset_face_data(m, d);
  SteadyStateOptions o;
  o.max_frames = 3000;
  const SteadyStateResult r = run_to_steady_state(m, d, face_input(*e), o);
  std::printf("converged %d frames %d residual %.4f\n", r.converged, r.frames, r.residual_mm);
  return e;
}

// One muscle's particles of head folder `dir`, at rest and at the steady state of a library
// expression (up to 3000 frames), in mm: two fitted folders' muscles compared particle by
// particle (docs/FACE_MODEL.md, "Bringing your own head").
int muscle_state(const char* dir, const char* expr, const char* name) {
  const HeadSpec spec = load_head_spec(dir);
  const FaceModel m = build_face_model(spec);
  const ExpressionLibrary lib = load_expression_library(library_path(), spec);
  FaceData d = make_face_data(m);
  if (settle_on(m, lib, expr, d) == nullptr) return 2;
  for (const Muscle& mu : m.muscles) {
    if (mu.name != name) continue;
    for (int k = 0; k < mu.particle_count(); ++k) {
      const Vec3 a = m.muscle_rest.get(static_cast<std::size_t>(mu.first + k)) * 1e3;
      const Vec3 b = d.muscles.get(static_cast<std::size_t>(mu.first + k)) * 1e3;
      std::printf("%d %.2f %.2f %.2f -> %.2f %.2f %.2f\n", k, a.x(), a.y(), a.z(), b.x(), b.y(),
                  b.z());
    }
  }
  return 0;
}

// Every anchor within `radius` (m) of each of `landmarks` at rest: its support, and how far
// its target has moved (x mirrored for the second landmark, the right mouth corner, so the
// two corners read alike).
void print_anchors_near(const FaceModel& m, const FaceData& d, const std::vector<int>& landmarks,
                        double radius) {
  for (std::size_t side = 0; side < landmarks.size(); ++side) {
    const Vec3 c = landmark_position(m, m.skin.v, landmarks[side]);
    for (std::size_t j = 0; j < m.anchors.size(); ++j) {
      const std::size_t i = static_cast<std::size_t>(m.anchors.particle[j]);
      const Vec3 rel = (m.skin.v.get(i) - c) * 1e3;
      if (rel.norm() > radius * 1e3) continue;
      const Vec3 t = d.anchor_targets.get(j) * 1e3, rest = m.skin.v.get(i) * 1e3;
      const double mirror = side ? -1 : 1;
      std::printf(
          "side %zu v%zu at %+.1f %+.1f %+.1f from it, on %s, target moved %.1f %.1f %.1f\n", side,
          i, mirror * rel.x(), rel.y(), rel.z(), anchor_support_name(m, j).c_str(),
          mirror * (t.x() - rest.x()), t.y() - rest.y(), t.z() - rest.z());
    }
  }
}

// After a run to steady state of library expression `expr` on head folder `dir` (3000
// frames at most): the mouth corners (fdp_8_3, fdp_8_4) over `frames` more frames, how
// many skin vertices each muscle carries, with FACE_CORNERS=R every anchor within R mm of
// a corner (its support and how far its target moved, x mirrored on the right), and the
// ten vertices that moved most over those frames (rest and current position, influence,
// support and target, nearest landmark). FACE_NEAR and FACE_POINTS: see the file's head.
int moving_skin(const char* dir, const char* expr, int frames) {
  const HeadSpec spec = load_head_spec(dir);
  const FaceModel m = build_face_model(spec);
  const ExpressionLibrary lib = load_expression_library(library_path(), spec);
  FaceData d = make_face_data(m);
  const Expression* e = settle_on(m, lib, expr, d);
  if (e == nullptr) return 2;
  const std::size_t n = d.skin_x.size();
  const Points start = d.skin_x;
  std::vector<double> moved(n, 0.0);
  const int corners[2] = {m.landmark_index("fdp_8_3"), m.landmark_index("fdp_8_4")};
  for (int f = 0; f < frames; ++f) {
    step_face(m, d, face_input(*e));
    for (std::size_t i = 0; i < n; ++i)
      moved[i] = std::max(moved[i], (d.skin_x.get(i) - start.get(i)).norm() * 1e3);
    const Vec3 a = landmark_position(m, d.skin_x, corners[0]) * 1e3;
    const Vec3 b = landmark_position(m, d.skin_x, corners[1]) * 1e3;
    std::printf("frame +%d corners %.2f %.2f %.2f | %.2f %.2f %.2f\n", f + 1, a.x(), a.y(), a.z(),
                b.x(), b.y(), b.z());
  }
  std::vector<int> bound(m.muscles.size(), 0);
  for (std::size_t j = 0; j < m.anchors.size(); ++j)
    if (const int k = anchor_muscle(m, j); k >= 0) ++bound[static_cast<std::size_t>(k)];
  for (std::size_t k = 0; k < m.muscles.size(); ++k)
    std::printf("%s binds %d skin vertices\n", m.muscles[k].name.c_str(), bound[k]);
  if (const char* r = std::getenv("FACE_CORNERS"))
    print_anchors_near(m, d, {corners[0], corners[1]}, std::atof(r) * 1e-3);
  // FACE_NEAR=fdp_2_10:12: the anchors within 12 mm of that landmark, as for the corners.
  if (const char* near = std::getenv("FACE_NEAR")) {
    const std::string arg = near;
    const std::size_t colon = arg.find(':');
    const int l = m.landmark_index(arg.substr(0, colon));
    if (l >= 0 && colon != std::string::npos)
      print_anchors_near(m, d, {l}, std::atof(arg.c_str() + colon + 1) * 1e-3);
  }
  // FACE_POINTS=fdp_8_2,fdp_2_10: those landmarks' displacements from rest, mm.
  if (const char* names = std::getenv("FACE_POINTS")) {
    std::string list = names;
    for (std::size_t at = 0; at <= list.size();) {
      const std::size_t end = std::min(list.find(',', at), list.size());
      const std::string name = list.substr(at, end - at);
      at = end + 1;
      if (const int l = m.landmark_index(name); l >= 0) {
        const Vec3 u =
            1e3 * (landmark_position(m, d.skin_x, l) - landmark_position(m, m.skin.v, l));
        std::printf("%s moved %+.2f %+.2f %+.2f mm\n", name.c_str(), u.x(), u.y(), u.z());
      }
    }
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto i, auto j) { return moved[i] > moved[j]; });
  for (std::size_t k = 0; k < 10 && k < n; ++k) {
    const std::size_t i = order[k];
    const Vec3 rest = m.skin.v.get(i) * 1e3, now = d.skin_x.get(i) * 1e3;
    std::string nearest;
    double best = 1e9;
    for (std::size_t l = 0; l < m.landmark_names.size(); ++l)
      for (int v : m.landmark_vertices[l]) {
        const double dist = (m.skin.v.get(static_cast<std::size_t>(v)) - m.skin.v.get(i)).norm();
        if (dist < best) best = dist, nearest = m.landmark_names[l];
      }
    std::string support = "none";
    for (std::size_t j = 0; j < m.anchors.size(); ++j) {
      if (m.anchors.particle[j] != static_cast<int>(i)) continue;
      const Vec3 t = d.anchor_targets.get(j) * 1e3;
      char where[96];
      std::snprintf(where, sizeof where, " target %.1f %.1f %.1f", t.x(), t.y(), t.z());
      support = anchor_support_name(m, j) + where;
    }
    std::printf(
        "v%zu moved %.3f mm rest %.1f %.1f %.1f now %.1f %.1f %.1f influence %.2f near %s "
        "(%.1f mm) on %s\n",
        i, moved[i], rest.x(), rest.y(), rest.z(), now.x(), now.y(), now.z(), m.influence[i],
        nearest.c_str(), best * 1e3, support.c_str());
  }
  return 0;
}

// Each muscle's rest particles against its mirror partner's (a `_l` muscle against its
// `_r`, a one-piece muscle against itself) reflected in x = 0: the largest distance from
// a particle of either to the nearest reflected particle of the other. On a head mirror-symmetric
// about x = 0 (the default is, to the bit) every gap should be 0.
int mirror_gaps(const char* dir) {
  const FaceModel m = build_face_model(load_head_spec(dir));
  auto find = [&](const std::string& name) -> const Muscle* {
    for (const Muscle& mu : m.muscles)
      if (mu.name == name) return &mu;
    return nullptr;
  };
  double worst = 0;
  for (const Muscle& mu : m.muscles) {
    if (mu.name.ends_with("_r")) continue;
    const std::string other =
        mu.name.ends_with("_l") ? mu.name.substr(0, mu.name.size() - 2) + "_r" : mu.name;
    const Muscle* partner = find(other);
    if (partner == nullptr) continue;
    // Both ways: from each particle to the nearest reflected particle of the other.
    auto one_way = [&](const Muscle& from, const Muscle& to) {
      double gap = 0;
      for (int i = 0; i < from.particle_count(); ++i) {
        Vec3 p = m.muscle_rest.get(static_cast<std::size_t>(from.first + i));
        p.x() = -p.x();
        double nearest = std::numeric_limits<double>::infinity();
        for (int j = 0; j < to.particle_count(); ++j)
          nearest = std::min(
              nearest, (m.muscle_rest.get(static_cast<std::size_t>(to.first + j)) - p).norm());
        gap = std::max(gap, nearest);
      }
      return gap;
    };
    const double gap = std::max(one_way(mu, *partner), one_way(*partner, mu));
    std::printf("%-40s %-40s %6.2f mm\n", mu.name.c_str(), other.c_str(), gap * 1e3);
    worst = std::max(worst, gap);
  }
  std::printf("largest mirror gap %.2f mm\n", worst * 1e3);
  return 0;
}

// N dense inputs (every muscle at c ~ U(0, 1), the jaw uniform) run to steady state under
// `passes` skin iterations and muscle passes a frame, then on under the head's solver: the
// skin's largest distance from the `passes` state after each of the head's first four
// frames (a state on a period-2 cycle of the head's frame reads far, near, far, near), then, after
// up to 2000 more frames of it, whether it settled and its farthest control point's distance from
// the `passes` state. A tolerance (mm over 20 frames) tightens both criteria and allows 8000
// frames. Per input, then a summary over the inputs settled under `passes`. For an input that
// alternates, also the vertex the head's first frame moves most, what its anchor rests on and
// how far it is from its anchor's target, and the largest such distance over the skin.
int passes_fixed_points(int n, unsigned seed, int passes, double tolerance_mm) {
  const HeadSpec spec = study_head_for(0);
  const FaceModel m = study_model(0);
  const std::vector<int> cps = control_landmarks(m);
  ReduceOptions ro;
  ro.active_probability = 1.0;
  ro.max_contraction = 1.0;
  FaceData d = make_face_data(m);
  SteadyStateOptions o, head;
  o.passes = {.skin = passes, .muscle = passes};
  if (tolerance_mm > 0) {
    o.tolerance_mm = head.tolerance_mm = tolerance_mm;
    o.max_frames = head.max_frames = 8000;
  }
  std::vector<double> first, ended;  // without a cycle; and of those, where the head settled
  int settled = 0, cycles = 0;
  for (const ReducedSample& s : random_samples(spec, ro, n, seed)) {
    FaceInput in;
    in.contractions = s.contractions;
    in.jaw = s.jaw;
    reset_face_data(m, d);
    const SteadyStateResult r = run_to_steady_state(m, d, in, o);
    const Points skin0 = d.skin_x;
    const std::vector<Vec3> cp0 = displacements(m, d, cps);
    // How far each vertex is from its anchor's target in the `passes` state.
    std::vector<double> gaps(skin0.size());
    for (std::size_t i = 0; i < gaps.size(); ++i)
      gaps[i] = 1e3 * (d.anchor_targets.get(i) - skin0.get(i)).norm();
    double away[4];
    std::size_t mover = 0;  // the vertex the head's first frame moves most
    for (int f = 0; f < 4; ++f) {
      step_face(m, d, in);
      std::size_t at = 0;
      away[f] = largest(d.skin_x, skin0, at);
      if (f == 0) mover = at;
    }
    const SteadyStateResult h = run_to_steady_state(m, d, in, head);
    const std::vector<Vec3> cp1 = displacements(m, d, cps);
    double cp_far = 0;
    for (std::size_t k = 0; k < cps.size(); ++k)
      cp_far = std::max(cp_far, (cp1[k] - cp0[k]).norm());
    const bool cycle = away[0] > 0.05 && away[1] < 0.5 * away[0] && away[2] > 0.5 * away[0] &&
                       away[3] < 0.5 * away[2];
    std::printf(
        "%s under %d | after the head's frames 1-4: skin %.3f %.3f %.3f %.3f mm away%s | "
        "head %s; farthest control point %.3f mm away\n",
        r.converged ? "settled  " : "UNSETTLED", passes, away[0], away[1], away[2], away[3],
        cycle ? " (alternating)" : "", h.converged ? "settles  " : "UNSETTLED", cp_far);
    if (cycle) {
      const Vec3 rest_mm = 1e3 * m.skin.v.get(mover);
      const std::size_t widest =
          static_cast<std::size_t>(std::max_element(gaps.begin(), gaps.end()) - gaps.begin());
      std::printf(
          "    moves most: vertex %zu (rest %.0f %.0f %.0f mm, on %s), %.2f mm from its anchor "
          "target; largest anchor gap %.2f mm at vertex %zu (on %s)\n",
          mover, rest_mm.x(), rest_mm.y(), rest_mm.z(), anchor_support_name(m, mover).c_str(),
          gaps[mover], gaps[widest], widest, anchor_support_name(m, widest).c_str());
    }
    if (!r.converged) continue;
    ++settled;
    if (cycle) {
      ++cycles;
      continue;
    }
    first.push_back(away[0]);
    if (h.converged) ended.push_back(cp_far);
  }
  std::printf(
      "%d of %d settled under %d passes; the head's frame takes %d of them away and back, "
      "frame after frame. Of the %zu others, the head's first frame takes the skin "
      "%.3f mm (median) and %.3f mm (at most) away; the head's solver settles %zu, "
      "their farthest control point ending %.3f mm (median) and %.3f mm (at most) "
      "from the %d-pass state\n",
      settled, n, passes, cycles, first.size(), percentile(first, 0.5),
      first.empty() ? 0.0 : *std::max_element(first.begin(), first.end()), ended.size(),
      percentile(ended, 0.5), ended.empty() ? 0.0 : *std::max_element(ended.begin(), ended.end()),
      passes);
  return 0;
}

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "muscle" && argc > 4) return muscle_state(argv[2], argv[3], argv[4]);
  if (mode == "mirror" && argc > 2) return mirror_gaps(argv[2]);
  if (mode == "skin" && argc > 3)
    return moving_skin(argv[2], argv[3], argc > 4 ? std::atoi(argv[4]) : 6);
  if (mode == "fixed")
    return passes_fixed_points(argc > 2 ? std::atoi(argv[2]) : 40,
                               argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1,
                               argc > 4 ? std::atoi(argv[4]) : 4,
                               argc > 5 ? std::atof(argv[5]) : 0);
  if (mode == "random")
    return random_study(argc > 2 ? std::atoi(argv[2]) : 100,
                        argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1,
                        argc > 4 ? static_cast<std::size_t>(std::atoi(argv[4])) : 0);
  if (mode == "muscles")
    return muscle_study(argc > 2 ? std::atoi(argv[2]) : 100,
                        argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1,
                        argc > 4 ? std::atoi(argv[4]) : 2000);
  if (mode == "mdetail")
    return muscle_detail(argc > 2 ? std::atoi(argv[2]) : 100,
                         argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1,
                         argc > 4 ? std::atoi(argv[4]) : 2000);
  if (mode == "trace" && argc > 2)
    return trace(argv[2], argc > 3 ? std::atoi(argv[3]) : 1000,
                 argc > 4 ? std::max(1, std::atoi(argv[4])) : 20,
                 !(argc > 5 && std::string(argv[5]) == "noteeth"));
  if (mode == "single") return single_study(argc > 2 ? std::atof(argv[2]) : 1.0);
  if (mode == "passes" && argc > 3) return passes_study(std::atoi(argv[2]), std::atoi(argv[3]));
  if (mode == "sensitivity")
    return sensitivity(argc > 2 ? std::atoi(argv[2]) : 20,
                       argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 1,
                       argc > 4 ? std::atof(argv[4]) : 1e-3);
  if (mode == "dump" && argc > 2)
    return dump(argv[2], argc > 3 ? std::atoi(argv[3]) : 2000, argc > 4 ? std::atoi(argv[4]) : 0,
                argc > 5 ? std::max(1, std::atoi(argv[5])) : 1);
  if (mode == "resolution" && argc > 2) {
    std::vector<std::size_t> sizes;
    for (int i = 2; i < argc; ++i) sizes.push_back(static_cast<std::size_t>(std::atoi(argv[i])));
    return resolution_study(sizes);
  }
  if (mode == "depth" && argc > 2) {
    std::vector<double> depths;
    for (int i = 2; i < argc; ++i) depths.push_back(std::atof(argv[i]));
    return depth_study(depths);
  }
  std::fprintf(stderr,
               "usage: face_convergence_probe random [N] [seed] [vertices]\n"
               "       face_convergence_probe muscles [N] [seed] [frames]\n"
               "       face_convergence_probe mdetail [N] [seed] [frames]\n"
               "       face_convergence_probe resolution V1 V2 ...   (0 = the base mesh)\n"
               "       face_convergence_probe depth MM1 MM2 ...   (skull tissue depths)\n"
               "       face_convergence_probe passes SKIN MUSCLE   (the library's settled states)\n"
               "       face_convergence_probe single [C]   (each muscle alone at C)\n"
               "       face_convergence_probe trace EXPRESSION|cp=C [frames] [stride] [noteeth]\n"
               "       face_convergence_probe sensitivity [N] [seed] [eps]\n"
               "       face_convergence_probe dump OUT.csv [samples] [shard] [shards]\n"
               "       face_convergence_probe muscle HEADDIR EXPRESSION MUSCLE\n"
               "       face_convergence_probe mirror HEADDIR\n"
               "       face_convergence_probe fixed [N] [seed] [passes] [tolerance_mm]\n");
  return 2;
}
