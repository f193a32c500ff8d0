#!/usr/bin/env bash
# Side by side, in one Google Benchmark run: the trajectory limiter step of
# REV (default: the commit before the working tree's HEAD) and of the working
# tree, with and without a jerk limit, on the same alternating targets. The
# old step is compiled from `git show REV:...` with its namespace renamed, so
# both live in one binary and see the same machine.
#
# Usage: scripts/compare_limiter_speed.sh [REV]
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-HEAD~1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

rename() { sed 's/namespace facectl\b/namespace facectl_old/; s|"control/actuator_model.hpp"|"old_actuator_model.hpp"|; s|"control/limits/trajectory_limiter.hpp"|"old_limiter.hpp"|'; }
git show "$rev:control/actuator_model.hpp" | rename > "$work/old_actuator_model.hpp"
git show "$rev:control/limits/trajectory_limiter.hpp" | rename > "$work/old_limiter.hpp"
git show "$rev:control/limits/trajectory_limiter.cpp" | rename > "$work/old_limiter.cpp"

cat > "$work/bench.cpp" <<'CPP'
#include <benchmark/benchmark.h>

#include "control/limits/trajectory_limiter.hpp"
#include "old_limiter.hpp"

template <class Limits, class State, class Step>
void run(benchmark::State& st, Step step) {
  const Limits l{-1, 1, -0.9, 0.9, 3.0, 50.0, static_cast<double>(st.range(0))};
  State s{};
  double target = 0.5;
  for (auto _ : st) {
    benchmark::DoNotOptimize(step(l, s, target, 0.001));
    if (s.position > 0.49) target = -0.5;
    if (s.position < -0.49) target = 0.5;
  }
}
void BM_LimitStepOld(benchmark::State& st) {
  run<facectl_old::ActuatorLimits, facectl_old::LimiterState>(st, facectl_old::limit_step);
}
void BM_LimitStepNew(benchmark::State& st) {
  run<facectl::ActuatorLimits, facectl::LimiterState>(st, facectl::limit_step);
}
// Arg: max_jerk (0 = none).
BENCHMARK(BM_LimitStepOld)->Arg(0)->Arg(2500);
BENCHMARK(BM_LimitStepNew)->Arg(0)->Arg(2500);
BENCHMARK_MAIN();
CPP
g++ -std=c++20 -O2 -DNDEBUG -I. -I"$work" "$work/bench.cpp" "$work/old_limiter.cpp" \
  control/limits/trajectory_limiter.cpp -lbenchmark -lpthread -o "$work/bench"
"$work/bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
