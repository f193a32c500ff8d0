// Face-model benchmarks (single thread): the full layered step at the skin sizes of the
// thesis's Table 5.1, skull + muscles alone, and the reduced model per control tick.
// Run: ./build/tests/bench_face  (not part of ctest; numbers in docs/PERFORMANCE.md)
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/reduced_model_fit.hpp"

namespace {

using namespace facectl::face;

const HeadSpec& spec() {
  static const HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  return s;
}

const FaceModel& model(std::size_t skin_vertices) {
  static std::map<std::size_t, std::unique_ptr<FaceModel>> cache;
  auto& p = cache[skin_vertices];
  if (!p) p = std::make_unique<FaceModel>(build_face_model(spec(), skin_vertices));
  return *p;
}

// A busy input: joy plus an open, shifted jaw, so every layer and the teeth work.
Expression busy() {
  const ExpressionLibrary lib =
      load_expression_library(FACECTL_CONFIG_DIR "/expressions/library.yaml", spec());
  Expression e = *lib.find("joy");
  e.jaw = {10 * 3.14159265 / 180, 2 * 3.14159265 / 180, 0.002};
  return e;
}

void BM_FullStep(benchmark::State& state) {
  const FaceModel& m = model(static_cast<std::size_t>(state.range(0)));
  FaceData d = make_face_data(m);
  const Expression e = busy();
  const FaceInput in = face_input(e);
  for (int f = 0; f < 50; ++f) step_face(m, d, in);
  for (auto _ : state) {
    step_face(m, d, in);
    benchmark::DoNotOptimize(d.skin_x.x.data());
  }
  state.counters["skin_vertices"] = static_cast<double>(m.skin.v.size());
  state.counters["constraints"] = static_cast<double>(
      m.skin_stretch.size() + m.skin_pair_stretch.k.size() + m.skin_bending.size() +
      m.skin_area.size() + m.skin_upright.size() + 1 + m.anchors.size());
}
BENCHMARK(BM_FullStep)
    ->Arg(0)
    ->Arg(1466)
    ->Arg(2502)
    ->Arg(4604)
    ->Arg(4904)
    ->Unit(benchmark::kMicrosecond);

void BM_SkullAndMuscles(benchmark::State& state) {
  const FaceModel& m = model(0);
  FaceData d = make_face_data(m);
  const Expression e = busy();
  const FaceInput in = face_input(e);
  for (int f = 0; f < 50; ++f) step_skull_and_muscles(m, d, in);
  std::size_t constraints = 0;
  for (const Muscle& mu : m.muscles)
    constraints += mu.distances.size() + mu.bending.size() + 1 + mu.attach.size();
  for (auto _ : state) {
    step_skull_and_muscles(m, d, in);
    benchmark::DoNotOptimize(d.muscles.x.data());
  }
  state.counters["muscle_particles"] = static_cast<double>(m.muscle_rest.size());
  state.counters["constraints"] = static_cast<double>(constraints);
}
BENCHMARK(BM_SkullAndMuscles)->Unit(benchmark::kMicrosecond);

void BM_ReducedPerTick(benchmark::State& state) {
  const ReducedFaceModel r =
      load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt", spec());
  ReducedFaceWorkspace w = make_reduced_workspace(r);
  const Expression e = busy();
  std::vector<double> out(3 * r.control_points.size());
  double phase = 0;
  for (auto _ : state) {
    phase += 1e-3;  // vary the input a little so nothing is hoisted
    ReducedInput in{e.contractions, e.jaw.pitch_rad + phase * 1e-3, e.jaw.yaw_rad,
                    e.jaw.protrusion_m};
    in.eyelid_closure[0] = e.eyelid_closure[0];
    in.eyelid_closure[1] = e.eyelid_closure[1];
    evaluate(r, w, in, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["control_points"] = static_cast<double>(r.control_points.size());
  state.counters["features"] = r.feature_count();
}
BENCHMARK(BM_ReducedPerTick)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
