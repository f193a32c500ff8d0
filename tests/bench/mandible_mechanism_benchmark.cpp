// Google Benchmark: the mandible mechanism's inverse kinematics in the tick
// (reachable and clamped targets) and verify's range proof. Results are
// recorded in docs/PERFORMANCE.md ("Mandible mechanism").
#include <benchmark/benchmark.h>

#include <numbers>
#include <vector>

#include "control/analysis/mechanism_range_proof.hpp"
#include "tests/support/mandible_mechanisms.hpp"

namespace facectl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// 256 targets on a sweep over 1.6 times the envelope, all of them reachable or all
// of them clamped (chosen before timing), solved in turn.
void run_solve(benchmark::State& state, std::size_t struts, bool want_clamped) {
  const MandibleMechanism m = testing::proposed_mechanism(struts);
  MandibleStrokes out{};
  std::vector<face::MandiblePose> targets;
  for (std::size_t i = 0; targets.size() < 256; ++i) {
    const double t = static_cast<double>(i % 97) / 96.0, u = static_cast<double>(i % 13) / 12.0;
    const face::MandiblePose target{(7 + 17.6 * (2 * t - 1)) * kDeg, 8 * (2 * u - 1) * kDeg,
                                    (4 + 6.4 * (1 - 2 * t)) * 1e-3};
    if (solve(m, target, out).clamped == want_clamped) targets.push_back(target);
  }
  std::size_t i = 0, iterations = 0;
  for (auto _ : state) {
    const MandibleSolveResult r = solve(m, targets[i++ % targets.size()], out);
    iterations += static_cast<std::size_t>(r.iterations);
    benchmark::DoNotOptimize(out);
  }
  state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(i);
}

void BM_MandibleSolveReachable(benchmark::State& state) {
  run_solve(state, 3, false);
}
BENCHMARK(BM_MandibleSolveReachable);

void BM_MandibleSolveClamped(benchmark::State& state) {
  run_solve(state, 3, true);
}
BENCHMARK(BM_MandibleSolveClamped);

void BM_MandibleSolveClamped2Strut(benchmark::State& state) {
  run_solve(state, 2, true);
}
BENCHMARK(BM_MandibleSolveClamped2Strut);

void BM_MandibleRangeProof(benchmark::State& state) {
  const MandibleMechanism m = testing::proposed_mechanism(3);
  std::size_t boxes = 0;
  for (auto _ : state) {
    const MechanismRangeProof proof = prove_stroke_ranges(m, MandibleEnvelope::design_default());
    boxes = proof.boxes;
    benchmark::DoNotOptimize(proof);
  }
  state.counters["boxes"] = static_cast<double>(boxes);
}
BENCHMARK(BM_MandibleRangeProof)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace facectl
