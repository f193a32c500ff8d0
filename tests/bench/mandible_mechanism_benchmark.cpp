// Google Benchmark: the mandible mechanism's inverse kinematics in the tick
// (reachable and clamped targets) and verify's range proof. Results are
// recorded in docs/PERFORMANCE.md ("Mandible mechanism").
#include <benchmark/benchmark.h>

#include <numbers>

#include "control/mechanism_range_proof.hpp"
#include "tests/support/mandible_mechanisms.hpp"

namespace facectl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Targets spread over the envelope (reachable) or beyond it (clamped).
void run_solve(benchmark::State& state, std::size_t struts, double reach) {
  const MandibleMechanism m = testing::proposed_mechanism(struts);
  MandibleStrokes out{};
  std::size_t i = 0, clamped = 0;
  for (auto _ : state) {
    const double t = static_cast<double>(i % 97) / 96.0, u = static_cast<double>(i % 13) / 12.0;
    const face::MandiblePose target{(7 + 11 * reach * (2 * t - 1)) * kDeg,
                                    5 * reach * (2 * u - 1) * kDeg,
                                    (4 + 4 * reach * (1 - 2 * t)) * 1e-3};
    const MandibleSolveResult r = solve(m, target, out);
    clamped += r.clamped ? 1 : 0;
    benchmark::DoNotOptimize(out);
    ++i;
  }
  state.counters["clamped"] = static_cast<double>(clamped) / static_cast<double>(i);
}

void BM_MandibleSolveReachable(benchmark::State& state) {
  run_solve(state, 3, 1.0);
}
BENCHMARK(BM_MandibleSolveReachable);

void BM_MandibleSolveClamped(benchmark::State& state) {
  run_solve(state, 3, 1.6);
}
BENCHMARK(BM_MandibleSolveClamped);

void BM_MandibleSolveClamped2Strut(benchmark::State& state) {
  run_solve(state, 2, 1.6);
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
