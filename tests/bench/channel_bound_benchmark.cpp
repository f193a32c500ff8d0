// Google Benchmark: verify's proven range of one control-point channel of the default
// head (reduced face model), over the muscle box and the mandible envelope, without and
// with coupled limits. Results are recorded in docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include "control/analysis/channel_bound.hpp"
#include "tests/support/default_face_space.hpp"

namespace facectl::verify {
namespace {

// Arg 0: 0 = lip corner 8.3 along +y (mm-scale pull), 1 = the same with a linear
// zygomaticus and pitch feed-forward plus the right corner. Arg 1: with coupled limits.
void BM_BoundControlPointChannel(benchmark::State& state) {
  const testing::DefaultFaceSpace& s = testing::default_face_space();
  ChannelTerms t;
  t.points = {{s.point("fdp_8_3"), {0, 1, 0}, 1.0}};
  if (state.range(0) == 1) {
    t.offset = 0.003;
    t.points = {{s.point("fdp_8_3"), {0, 1, 0}, 0.5}, {s.point("fdp_8_4"), {0, 1, 0}, 0.5}};
    t.linear = {{s.muscle("zygomaticus_major_l"), 0.01}, {s.n, -0.02}};
  }
  const ChannelPolynomial p = make_channel_polynomial(s.model, t);
  const std::vector<LinearInequality> rows =
      state.range(1) ? s.coupled_limits() : std::vector<LinearInequality>{};
  long boxes = 0;
  bool converged = true;
  for (auto _ : state) {
    const ChannelBound b = bound_channel(p, s.box, rows);
    boxes = b.boxes_used;
    converged = converged && b.converged;
    benchmark::DoNotOptimize(b.upper);
  }
  state.counters["boxes"] = static_cast<double>(boxes);
  state.counters["converged"] = converged ? 1 : 0;
}
BENCHMARK(BM_BoundControlPointChannel)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

void BM_MakeChannelPolynomial(benchmark::State& state) {
  const testing::DefaultFaceSpace& s = testing::default_face_space();
  ChannelTerms t;
  t.points = {{s.point("fdp_8_3"), {0, 1, 0}, 1.0}};
  for (auto _ : state) benchmark::DoNotOptimize(make_channel_polynomial(s.model, t).terms.size());
}
BENCHMARK(BM_MakeChannelPolynomial)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace facectl::verify
