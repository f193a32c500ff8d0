// Time per frame of the face render sequence (docs/PERFORMANCE.md, "Render
// frames"): a warm frame at the default 400x400 views, and the inverse mapping
// alone. Built, not run by ctest.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "control/mapping/rig_mapping.hpp"
#include "firmware-host/simulate/mapping_inverse.hpp"
#include "firmware-host/simulate/render_sequence.hpp"

namespace facectl {
namespace {

using Face = std::array<double, kMaxFaceSignals>;
using Positions = std::array<double, kMaxActuators>;

const LoadedConfig& config() {
  static const LoadedConfig c = load_config(default_config_path());
  return c;
}

// Two faces a frame apart in a lively show: a smile with the jaw opening, and neutral.
std::array<std::pair<Face, Positions>, 2> two_frames() {
  const ControllerModel& m = config().built.model;
  Face smile = m.neutral;
  for (const char* name : {"zygomaticus_major_l", "zygomaticus_major_r"}) {
    smile[*m.layout.find(name)] = 0.7;
  }
  smile[m.layout.jaw_pitch()] = 10 * std::numbers::pi / 180;
  MappingWorkspace w = make_mapping_workspace(m.mapping);
  std::array<std::pair<Face, Positions>, 2> out{};
  out[0].first = smile;
  out[1].first = m.neutral;
  for (auto& [f, p] : out) map_to_actuators(m.mapping, w, f, p);
  return out;
}

void BM_RenderFrame(benchmark::State& state) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("facectl-bench-render-" + std::to_string(getpid()));
  const auto frames = two_frames();
  RenderSequence seq(config(), dir);
  seq.add_frame(frames[1].first, frames[1].second);  // the first frame starts from rest
  std::size_t k = 0;
  for (auto _ : state) {
    seq.add_frame(frames[k % 2].first, frames[k % 2].second);
    ++k;
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_RenderFrame)->Unit(benchmark::kMillisecond);

// A frame of a smooth show: the smile of two_frames() eased in and out over
// 2 s at 25 frames a second, so consecutive frames differ a little.
void BM_RenderSmoothFrame(benchmark::State& state) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("facectl-bench-smooth-" + std::to_string(getpid()));
  const auto frames = two_frames();
  const ControllerModel& m = config().built.model;
  MappingWorkspace w = make_mapping_workspace(m.mapping);
  RenderSequence seq(config(), dir);
  seq.add_frame(frames[1].first, frames[1].second);
  std::size_t k = 0;
  Face face{};
  Positions positions{};
  for (auto _ : state) {
    const double u = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(k++) / 50);
    for (std::size_t s = 0; s < m.layout.size(); ++s) {
      face[s] = frames[1].first[s] + u * (frames[0].first[s] - frames[1].first[s]);
    }
    map_to_actuators(m.mapping, w, face, positions);
    seq.add_frame(face, positions);
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_RenderSmoothFrame)->Unit(benchmark::kMillisecond);

void BM_FirstFrame(benchmark::State& state) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("facectl-bench-first-" + std::to_string(getpid()));
  const auto frames = two_frames();
  for (auto _ : state) {
    RenderSequence seq(config(), dir);
    seq.add_frame(frames[0].first, frames[0].second);
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_FirstFrame)->Unit(benchmark::kMillisecond);

void BM_InvertMapping(benchmark::State& state) {
  const MappingInverse inv = make_mapping_inverse(config().built.model);
  auto w = std::make_unique<MappingInverseWorkspace>(make_mapping_inverse_workspace(inv));
  const auto frames = two_frames();
  Face face{};
  for (auto _ : state) {
    invert_mapping(inv, *w, frames[0].second, face);
    benchmark::DoNotOptimize(face);
  }
}
BENCHMARK(BM_InvertMapping)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace facectl
