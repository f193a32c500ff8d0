// Google Benchmark: one controller tick of the default head on simulated
// hardware, and its parts. Results are recorded in docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include "control/limits/trajectory_limiter.hpp"
#include "tests/support/sim_head.hpp"

namespace facectl {
namespace {

void BM_ControllerTick(benchmark::State& state) {
  testing::SimHead head(default_config_path(), 1 << 12);
  auto pose = head.model().neutral;
  head.controller().request_enable();
  head.run_for(1.5);
  std::size_t i = 0;
  for (auto _ : state) {
    pose[i % head.model().layout.muscle_count()] = static_cast<double>(i % 10) / 10.0;
    // The jaw sweeps too, so the mandible mechanism's limiter and IK work.
    pose[head.model().layout.jaw_pitch()] = 0.25 * static_cast<double>(i % 2000) / 2000.0;
    head.send(pose);
    head.step(head.period());
    if (head.telemetry()->front() != nullptr) head.telemetry()->pop();
    ++i;
  }
}
BENCHMARK(BM_ControllerTick);

void BM_LimitStep(benchmark::State& state) {
  ActuatorLimits l{-1, 1, -0.9, 0.9, 3.0, 50.0, 0.0};
  LimiterState s;
  double target = 0.5;
  for (auto _ : state) {
    benchmark::DoNotOptimize(limit_step(l, s, target, 0.001));
    if (s.position > 0.49) target = -0.5;
    if (s.position < -0.49) target = 0.5;
  }
}
BENCHMARK(BM_LimitStep);

}  // namespace
}  // namespace facectl
