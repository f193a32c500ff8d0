#include "reduce_command.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "face_command_support.hpp"
#include "facectl/face/expression_library.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "facectl/face/reduced_test_sets.hpp"

namespace {

using namespace facectl::face;
using namespace facectl::face_cli;

// Prints one line per named set; true when every set meets the targets.
bool print_set_errors(const std::vector<SetError>& errors, double rms_mm, double p99_mm) {
  bool ok = true;
  std::printf("%-20s %7s %9s %8s %8s %8s %8s  %s\n", "set", "samples", "unsettled", "measured",
              "rms_mm", "p99_mm", "max_mm", "worst");
  for (const SetError& e : errors) {
    if (e.measured == 0) {  // --settled-only and nothing settled: no error to judge
      ok = false;
      std::printf("%-20s %7d %9d %8d %8s %8s %8s  (no settled run)\n", e.name.c_str(), e.samples,
                  e.unsettled, e.measured, "-", "-", "-");
      continue;
    }
    const bool pass = e.rms_mm <= rms_mm && e.p99_mm <= p99_mm;
    ok = ok && pass;
    std::printf("%-20s %7d %9d %8d %8.3f %8.3f %8.3f  %s%s\n", e.name.c_str(), e.samples,
                e.unsettled, e.measured, e.rms_mm, e.p99_mm, e.max_mm, e.worst.c_str(),
                pass ? "" : "  (over target)");
  }
  return ok;
}

// The full-model runs' threads; the results do not depend on it.
void threads_option(CLI::App* app, int& threads) {
  app->add_option("--threads", threads,
                  "threads for the full-model runs (0: one per core; the results are the same)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

}  // namespace

void add_reduce_commands(CLI::App* face) {
  static FaceArgs args = default_face_args();
  static std::string reduced_out;
  static ReduceOptions ro;
  static double max_rms_mm = 0;
  CLI::App* reduce =
      face->add_subcommand("reduce", "fit the reduced real-time model to the full model");
  add_common(reduce, args);
  cap_frames_option(reduce, ro.steady.max_frames);
  reduce->add_option("--out", reduced_out, "output file (default <head>/reduced_face.txt)");
  reduce->add_option("--samples", ro.train_samples, "training inputs")->capture_default_str();
  reduce->add_option("--test-samples", ro.test_samples, "held-out inputs")->capture_default_str();
  reduce->add_option("--seed", ro.seed)->capture_default_str();
  threads_option(reduce, ro.threads);
  reduce->add_option("--check-rms-mm", max_rms_mm, "exit 1 if the held-out RMS error exceeds this");
  reduce
      ->add_option("--tolerance-mm", ro.steady.tolerance_mm,
                   "a sample is settled when no skin vertex moved more than this over the "
                   "last 20 frames")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  passes_option(reduce, ro.steady.passes);
  reduce->callback([reduce] {
    guarded("reduce", [reduce] {
      const HeadSpec spec = load_head_spec(args.head);
      // The file does not record a resolution, and none has converged (docs/FACE_MODEL.md,
      // "Known issues"): the model is fitted on the base mesh, which is also the fastest.
      if (args.resolution != 0)
        throw std::invalid_argument("--resolution " + std::to_string(args.resolution) +
                                    ": the reduced model is fitted on the base mesh; "
                                    "check-reduced --resolution measures it against a finer one");
      const FaceModel m = build_face_model(spec);
      // Each sample runs to a steady state; --frames, if given, caps it.
      if (reduce->count("--frames") > 0) ro.steady.max_frames = args.frames;
      ReduceReport r;
      const auto t0 = std::chrono::steady_clock::now();
      const ReducedFaceModel red = build_reduced_model(m, ro, &r);
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const std::string path = reduced_out.empty() ? args.head + "/reduced_face.txt" : reduced_out;
      save_reduced_model(red, path);
      std::printf(
          "wrote %s: %zu control points, %d features; train (%d) RMS %.3f mm; held-out (%d) RMS "
          "%.3f mm, median %.3f mm, 95th percentile %.3f mm, max %.3f mm; %d full-model runs "
          "unsettled (largest residual %.3f mm); %.1f s\n",
          path.c_str(), red.control_points.size(), red.feature_count(), r.train_samples,
          r.train_rms_mm, r.test_samples, r.test_rms_mm, r.test_median_mm, r.test_p95_mm,
          r.test_max_mm, r.unsettled_runs, r.worst_residual_mm, secs);
      // The same named sets as check-reduced, with its defaults.
      const ExpressionLibrary lib = load_expression_library(args.library, spec);
      print_set_errors(reduced_errors(m, red, reduced_test_sets(spec, lib, 200, 1), ro.steady,
                                      false, ro.threads),
                       0.5, 2.0);
      if (max_rms_mm > 0 && r.test_rms_mm > max_rms_mm) {
        std::fprintf(stderr, "facectl face reduce: held-out RMS %.3f mm exceeds %.3f mm\n",
                     r.test_rms_mm, max_rms_mm);
        throw CLI::RuntimeError(1);
      }
    });
  });

  static std::string check_json;
  static int check_samples = 200;
  static unsigned check_seed = 1;
  static double target_rms_mm = 0.5, target_p99_mm = 2.0;
  CLI::App* check = face->add_subcommand(
      "check-reduced", "the shipped reduced model's error against the full model, per test set");
  add_common(check, args);
  cap_frames_option(check, SteadyStateOptions{}.max_frames);
  check->add_option("--samples", check_samples, "inputs in each random set")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  check->add_option("--seed", check_seed)->capture_default_str();
  static int check_threads = 0;
  threads_option(check, check_threads);
  check->add_option("--json", check_json, "also write the errors as JSON, keyed by set name");
  check->add_option("--rms-mm", target_rms_mm, "exit 1 if a set's RMS error exceeds this")
      ->capture_default_str();
  check->add_option("--p99-mm", target_p99_mm, "exit 1 if a set's 99th percentile exceeds this")
      ->capture_default_str();
  static SolverPasses check_passes = ReduceOptions{}.steady.passes;
  passes_option(check, check_passes);
  static bool settled_only = false;
  check->add_flag("--settled-only", settled_only,
                  "leave the full-model runs that did not settle out of the errors (a set "
                  "with none settled fails; no run settles before 60 frames)");
  check->callback([check] {
    guarded("check-reduced", [check] {
      const HeadSpec spec = load_head_spec(args.head);
      const ReducedFaceModel red = load_reduced_model(args.head + "/reduced_face.txt", spec);
      const FaceModel m =
          build_face_model(spec, static_cast<std::size_t>(std::max(0, args.resolution)));
      const ExpressionLibrary lib = load_expression_library(args.library, spec);
      // Each input runs to a steady state; --frames, if given, caps it.
      SteadyStateOptions steady;
      steady.passes = check_passes;
      if (check->count("--frames") > 0) steady.max_frames = args.frames;
      const auto errors =
          reduced_errors(m, red, reduced_test_sets(spec, lib, check_samples, check_seed), steady,
                         settled_only, check_threads);
      const bool ok = print_set_errors(errors, target_rms_mm, target_p99_mm);
      if (!check_json.empty()) write_text_file(check_json, set_errors_json(errors));
      if (!ok) {
        std::fprintf(stderr,
                     "facectl face check-reduced: a set is over %.3f mm RMS or %.3f mm at the "
                     "99th percentile, or has no settled run\n",
                     target_rms_mm, target_p99_mm);
        throw CLI::RuntimeError(1);
      }
    });
  });
}
