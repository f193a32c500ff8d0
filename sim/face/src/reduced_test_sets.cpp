#include "facectl/face/reduced_test_sets.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>

#include "control/envelope/mandible_envelope.hpp"
#include "control/units.hpp"
#include "facectl/face/full_model_runs.hpp"

namespace facectl::face {

namespace {

ReducedSample relaxed(const HeadSpec& head) {
  ReducedSample s;
  s.contractions.assign(head.commanded.size(), 0.0);
  return s;
}

std::vector<ReducedSample> random_set(const HeadSpec& head, double active, double max_c, bool lids,
                                      int n, unsigned seed) {
  ReduceOptions o;
  o.active_probability = active;
  o.max_contraction = max_c;
  o.random_eyelids = lids;
  return random_samples(head, o, n, seed);
}

}  // namespace

std::vector<NamedSampleSet> reduced_test_sets(const HeadSpec& head,
                                              const ExpressionLibrary& library, int n,
                                              unsigned seed) {
  std::vector<NamedSampleSet> sets;
  sets.push_back({"in_distribution",
                  "35% of muscles active at c ~ U(0, 0.7), jaw uniform, eyes open",
                  random_set(head, 0.35, 0.7, false, n, seed + 101)});
  sets.push_back({"sparse_uniform", "35% of muscles active at c ~ U(0, 1), jaw and eyelids uniform",
                  random_set(head, 0.35, 1.0, true, n, seed + 202)});
  sets.push_back({"dense_uniform", "every muscle at c ~ U(0, 1), jaw and eyelids uniform",
                  random_set(head, 1.0, 1.0, true, n, seed + 303)});

  NamedSampleSet single{"single_muscle_full", "each muscle alone at c = 1, jaw at rest", {}};
  for (std::size_t i = 0; i < head.commanded.size(); ++i) {
    ReducedSample s = relaxed(head);
    s.contractions[i] = 1.0;
    single.samples.push_back(std::move(s));
  }
  sets.push_back(std::move(single));

  // The envelope's corners, relaxed and under a random sparse mix.
  NamedSampleSet corners{
      "jaw_corners", "the 8 corners of the mandible envelope, relaxed and with a sparse mix", {}};
  const std::vector<ReducedSample> mixes = random_set(head, 0.35, 1.0, false, 8, seed + 404);
  for (int k = 0; k < 16; ++k) {
    ReducedSample s = k < 8 ? relaxed(head) : mixes[static_cast<std::size_t>(k - 8)];
    const int c = k % 8;
    s.jaw.pitch_rad = ((c & 1) ? kJawPitchMaxDeg : kJawPitchMinDeg) * kDeg;
    s.jaw.yaw_rad = ((c & 2) ? kJawYawMaxDeg : -kJawYawMaxDeg) * kDeg;
    s.jaw.protrusion_m = (c & 4) ? kJawProtrusionMaxMm * 1e-3 : 0.0;
    corners.samples.push_back(std::move(s));
  }
  sets.push_back(std::move(corners));

  NamedSampleSet lib{"library", "every expression of the library, with its eyelids", {}};
  for (const Expression& e : library.expressions) {
    ReducedSample s;
    s.contractions = e.contractions;
    s.jaw = e.jaw;
    s.eyelid_closure[0] = e.eyelid_closure[0];
    s.eyelid_closure[1] = e.eyelid_closure[1];
    lib.samples.push_back(std::move(s));
  }
  sets.push_back(std::move(lib));
  return sets;
}

std::vector<SetError> reduced_errors(const FaceModel& full, const ReducedFaceModel& reduced,
                                     const std::vector<NamedSampleSet>& sets,
                                     const SteadyStateOptions& steady, bool settled_only,
                                     int threads) {
  const std::vector<int> cps = full.landmark_indices(reduced.control_points);
  ReducedFaceWorkspace w = make_reduced_workspace(reduced);
  std::vector<double> predicted(3 * cps.size());
  std::vector<SetError> out;
  for (const NamedSampleSet& set : sets) {
    SetError e;
    e.name = set.name;
    e.samples = static_cast<int>(set.samples.size());
    std::vector<double> errors;
    double sum = 0;
    const FullModelRuns runs = run_full_model(full, cps, set.samples, steady, threads);
    for (std::size_t k = 0; k < set.samples.size(); ++k) {
      const std::vector<double>& truth = runs.responses[k];
      e.unsettled += runs.settled[k].converged ? 0 : 1;
      if (settled_only && !runs.settled[k].converged) continue;
      ++e.measured;
      evaluate(reduced, w, reduced_input(set.samples[k]), predicted);
      for (std::size_t p = 0; p < cps.size(); ++p) {
        const double dx = predicted[3 * p] - truth[3 * p];
        const double dy = predicted[3 * p + 1] - truth[3 * p + 1];
        const double dz = predicted[3 * p + 2] - truth[3 * p + 2];
        const double mm = 1e3 * std::sqrt(dx * dx + dy * dy + dz * dz);
        sum += mm * mm;
        if (mm > e.max_mm) {
          e.max_mm = mm;
          e.worst = reduced.control_points[p] + " in sample " + std::to_string(k);
        }
        errors.push_back(mm);
      }
    }
    if (!errors.empty()) {
      std::sort(errors.begin(), errors.end());
      e.rms_mm = std::sqrt(sum / static_cast<double>(errors.size()));
      // Nearest-rank 99th percentile.
      const auto rank =
          static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(errors.size())));
      e.p99_mm = errors[std::max<std::size_t>(rank, 1) - 1];
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::string set_errors_json(const std::vector<SetError>& errors) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const SetError& e : errors) {
    j[e.name] = {{"samples", e.samples}, {"unsettled", e.unsettled}, {"measured", e.measured},
                 {"rms_mm", e.rms_mm},   {"p99_mm", e.p99_mm},       {"max_mm", e.max_mm},
                 {"worst", e.worst}};
    if (e.measured == 0)  // no error was measured: not a perfect fit
      for (const char* k : {"rms_mm", "p99_mm", "max_mm"}) j[e.name][k] = nullptr;
  }
  return j.dump(2) + "\n";
}

}  // namespace facectl::face
