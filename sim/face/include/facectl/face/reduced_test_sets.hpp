// The named input sets on which the reduced face model is judged against the full model
// (`facectl face reduce` and `facectl face check-reduced`), and the errors per set. Together
// they cover the admissible domain: contractions anywhere in [0, 1], in any mix, the whole
// mandible envelope and the library's expressions with their eyelids.
#pragma once

#include <string>
#include <vector>

#include "control/face/reduced_face_model.hpp"
#include "facectl/face/expression_library.hpp"
#include "facectl/face/reduced_model_fit.hpp"

namespace facectl::face {

struct NamedSampleSet {
  std::string name;
  std::string description;
  std::vector<ReducedSample> samples;
};

// in_distribution (35% of muscles active, c ~ U(0, 0.7), jaw uniform), sparse_uniform (35%
// active, c ~ U(0, 1)), dense_uniform (every muscle c ~ U(0, 1)), single_muscle_full (each
// muscle alone at 1, jaw at rest), jaw_corners (the 8 corners of the mandible envelope,
// relaxed and with a random sparse mix each), library (every expression of `library`).
// `random_samples` inputs in each random set; seeds differ from the fit's.
std::vector<NamedSampleSet> reduced_test_sets(const HeadSpec& head,
                                              const ExpressionLibrary& library, int random_samples,
                                              unsigned seed);

struct SetError {
  std::string name;
  int samples = 0;
  double rms_mm = 0, p99_mm = 0, max_mm = 0;  // of the per-point 3-D errors
  std::string worst;                          // "point in sample k" of the maximum
  int unsettled = 0;                          // full-model runs that did not reach the steady state
  int measured = 0;                           // runs the errors are over
};

// The reduced model against the full model's steady state on each set; each set
// reports how many full-model runs did not settle. With `settled_only` the errors leave
// those runs out: what the model's form misses where the truth is a steady state, apart
// from the snapshots of a still-moving skin. The full-model runs go on `threads` threads
// (run_full_model; <= 0: one per core); the errors do not depend on it.
std::vector<SetError> reduced_errors(const FaceModel& full, const ReducedFaceModel& reduced,
                                     const std::vector<NamedSampleSet>& sets,
                                     const SteadyStateOptions& steady, bool settled_only = false,
                                     int threads = 0);

// The sets' errors as a JSON object keyed by set name.
std::string set_errors_json(const std::vector<SetError>& errors);

}  // namespace facectl::face
