// Google Benchmark: verify's proven range of one control-point channel of the default
// head (reduced face model), over the muscle box and the mandible envelope, without and
// with coupled limits. Results are recorded in docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "facectl/face/head_spec.hpp"
#include "firmware-host/verify/channel_bound.hpp"

namespace facectl::verify {
namespace {

struct Setup {
  face::ReducedFaceModel model;
  int n = 0;
  std::vector<Interval> box;
  std::vector<LinearInequality> coupled;
  int muscle(const char* name) const {
    for (int i = 0; i < n; ++i)
      if (model.muscles[static_cast<std::size_t>(i)] == name) return i;
    return -1;
  }
  int point(const char* name) const {
    for (std::size_t i = 0; i < model.control_points.size(); ++i)
      if (model.control_points[i] == name) return static_cast<int>(i);
    return -1;
  }
};

const Setup& setup() {
  static const Setup s = [] {
    constexpr double kDeg = std::numbers::pi / 180;
    Setup r;
    r.model = face::load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt",
                                       face::load_head_spec(FACECTL_DEFAULT_HEAD_DIR));
    r.n = static_cast<int>(r.model.muscles.size());
    r.box.assign(static_cast<std::size_t>(r.n), Interval{0, 1});
    r.box.push_back({-4 * kDeg, 18 * kDeg});
    r.box.push_back({-5 * kDeg, 5 * kDeg});
    r.box.push_back({0, 0.008});
    const auto N = static_cast<std::size_t>(r.n + 3);
    LinearInequality antagonists{std::vector<double>(N, 0.0), 1.0};
    antagonists.a[static_cast<std::size_t>(r.muscle("zygomaticus_major_l"))] = 1;
    antagonists.a[static_cast<std::size_t>(r.muscle("depressor_anguli_oris_l"))] = 1;
    LinearInequality yaw_up{std::vector<double>(N, 0.0), 0.05}, yaw_down = yaw_up;
    yaw_up.a[static_cast<std::size_t>(r.n + 1)] = 1;  // |yaw| ≤ 0.05 + 0.3·pitch
    yaw_up.a[static_cast<std::size_t>(r.n)] = -0.3;
    yaw_down.a[static_cast<std::size_t>(r.n + 1)] = -1;
    yaw_down.a[static_cast<std::size_t>(r.n)] = -0.3;
    r.coupled = {antagonists, yaw_up, yaw_down};
    return r;
  }();
  return s;
}

// Arg 0: 0 = lip corner 8.3 along +y (mm-scale pull), 1 = the same with a linear
// zygomaticus and pitch feed-forward plus the right corner. Arg 1: with coupled limits.
void BM_BoundControlPointChannel(benchmark::State& state) {
  const Setup& s = setup();
  ChannelTerms t;
  t.points = {{s.point("fdp_8_3"), {0, 1, 0}, 1.0}};
  if (state.range(0) == 1) {
    t.offset = 0.003;
    t.points = {{s.point("fdp_8_3"), {0, 1, 0}, 0.5}, {s.point("fdp_8_4"), {0, 1, 0}, 0.5}};
    t.linear = {{s.muscle("zygomaticus_major_l"), 0.01}, {s.n, -0.02}};
  }
  const ChannelPolynomial p = make_channel_polynomial(s.model, t);
  const std::span<const LinearInequality> rows = state.range(1)
                                                     ? std::span<const LinearInequality>(s.coupled)
                                                     : std::span<const LinearInequality>();
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
  const Setup& s = setup();
  ChannelTerms t;
  t.points = {{s.point("fdp_8_3"), {0, 1, 0}, 1.0}};
  for (auto _ : state) benchmark::DoNotOptimize(make_channel_polynomial(s.model, t).terms.size());
}
BENCHMARK(BM_MakeChannelPolynomial)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace facectl::verify
