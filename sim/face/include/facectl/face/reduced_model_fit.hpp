// Fitting the reduced face model (control/face/reduced_face_model.hpp) by least squares to
// full-model steady states, and its file. Each control point is fitted only on the muscles
// that move it (by a single-muscle probe of the full model), so unrelated muscles cannot add
// noise.
#pragma once

#include <string>
#include <vector>

#include "control/face/reduced_face_model.hpp"
#include "facectl/face/face_model.hpp"
#include "facectl/face/steady_state.hpp"

namespace facectl::face {

// Constraint passes a frame of the fit's and check-reduced's steady-state runs.
constexpr int kSteadyPasses = 4;

struct ReduceOptions {
  int train_samples = 2000, test_samples = 200;
  // When a sample's full-model run counts as settled. Four skin and muscle passes a frame:
  // the head solver's steady states, and more inputs settle, in fewer frames
  // (docs/FACE_MODEL.md, "Passes a frame for steady states").
  SteadyStateOptions steady = {.passes = {.skin = kSteadyPasses, .muscle = kSteadyPasses}};
  double active_probability = 0.35, max_contraction = 0.7;
  bool random_eyelids = false;  // random_samples: each lid closed to U(0, 1), else open
  unsigned seed = 1;
  double ridge = 1e-6;
  // Least-squares weight of each single-muscle and single-lid sweep against a mix's 1: the
  // one-signal responses are what a rig's directions and calibration are checked on.
  double sweep_weight = 10;
  double relevance_mm = 0.3;  // a muscle moves a point if c = 1 alone moves it this much
  // Threads for the full-model runs (run_full_model; <= 0: one per core). The model does
  // not depend on it.
  int threads = 0;
};

struct ReduceReport {
  double train_rms_mm = 0, test_rms_mm = 0, test_max_mm = 0;
  double test_median_mm = 0, test_p95_mm = 0;  // of the per-point 3-D errors
  int train_samples = 0, test_samples = 0;
  // Full-model runs (probes, training and held-out samples) that reached
  // steady.max_frames without settling, and the largest residual any run ended with.
  int unsettled_runs = 0;
  double worst_residual_mm = 0;
};

// One random input of the distribution used for fitting and testing.
struct ReducedSample {
  std::vector<double> contractions;
  MandiblePose jaw;
  double eyelid_closure[2] = {0, 0};  // left, right
};
// The reduced model's input for a sample (which must outlive it).
ReducedInput reduced_input(const ReducedSample& s);
// The fit's inputs: n mixes from sparse to dense with c ~ U(0, 1), the jaw over its envelope
// and each eyelid over [0, 1] with their limits weighted, then (single_muscle_sweeps) each
// muscle and each eyelid alone at 0.25, 0.5, 0.75 and 1.
std::vector<ReducedSample> training_samples(const HeadSpec& head, int n, unsigned seed,
                                            bool single_muscle_sweeps);
std::vector<ReducedSample> random_samples(const HeadSpec& head, const ReduceOptions& o, int n,
                                          unsigned seed);
// Full-model steady-state control-point displacements (m) for one sample, run from rest
// by run_to_steady_state(); `settled`, if given, receives how it ended. Without
// `teeth_collision` the lips pass through the teeth (a study knob).
std::vector<double> full_model_response(const FaceModel& m, FaceData& d,
                                        const std::vector<int>& control_landmarks,
                                        const ReducedSample& s, const SteadyStateOptions& steady,
                                        SteadyStateResult* settled = nullptr,
                                        bool teeth_collision = true);

ReducedFaceModel build_reduced_model(const FaceModel& full, const ReduceOptions& o,
                                     ReduceReport* report);
void save_reduced_model(const ReducedFaceModel& m, const std::string& path);
// Throws InputError naming file:line when the file is malformed, does not match `head`, or
// was fitted to head files that have changed since (stale).
ReducedFaceModel load_reduced_model(const std::string& path, const HeadSpec& head);

}  // namespace facectl::face
