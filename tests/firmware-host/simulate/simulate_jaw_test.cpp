// An MPEG-4 FAP jaw opening through `facectl simulate`: the mandible, as the
// forward kinematics of the simulated strut positions gives it, reaches the
// pitch that open_jaw asks for (from the FAPU definition, docs/FAP.md) within 0.1°.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/mapping/mandible_mechanism.hpp"
#include "facectl/face/head_spec.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/fap/fapu.hpp"
#include "firmware-host/report/telemetry_csv.hpp"
#include "simulate_process.hpp"
#include "tests/support/jaw_geometry.hpp"

namespace facectl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr int kFapCount = 68;

// open_jaw ramps from 0 to `units` over 1 s, then holds for 2 s (25 fps).
std::string jaw_opening(int units) {
  std::string text = "2.1 jaw_opening 25 75\n";
  std::string mask;
  for (int i = 0; i < kFapCount; ++i) mask += std::string(i ? " " : "") + (i == 2 ? "1" : "0");
  for (int k = 0; k < 75; ++k) {
    const int v = static_cast<int>(std::lround(units * std::min(1.0, k / 25.0)));
    text += mask + "\n" + std::to_string(k) + " " + std::to_string(v) + "\n";
  }
  return text;
}

class SimulateJaw : public ::testing::TestWithParam<int> {};

TEST_P(SimulateJaw, OpenJawMovesTheMandibleToTheGeometricPitch) {
  const int units = GetParam();
  testing::TempDir tmp;
  testing::write_text(tmp / "jaw.fap", jaw_opening(units));
  const auto r =
      testing::run_facectl({"simulate", "--rig", testing::source_path("config/rigs/default.yaml"),
                            "--fap", tmp / "jaw.fap", "--out", tmp / "out"},
                           tmp / "log");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const FeaturePoints fp =
      FeaturePoints::load(face::load_head_spec(testing::source_path("config/heads/default")));
  const double want = testing::expected_jaw_pitch(fp, units * testing::mns0(fp) / 1024.0);
  ASSERT_GT(want / kDeg, 2.0);  // a real opening

  const LoadedConfig cfg = load_config(default_config_path());
  ASSERT_TRUE(cfg.built.model.mapping.mechanism.has_value());
  const MandibleMechanism& mech = *cfg.built.model.mapping.mechanism;
  const TelemetryTable t = read_telemetry_csv(tmp / "out/telemetry.csv");
  MandibleStrokes strokes{};
  for (std::size_t s = 0; s < mech.struts(); ++s) {
    const std::string name = cfg.built.model.actuators[mech.strut[s].actuator].name;
    strokes[s] = t.numbers("pos." + name).back();
  }
  const auto pose = forward(mech, strokes);
  ASSERT_TRUE(pose.has_value());
  EXPECT_NEAR(pose->pitch_rad / kDeg, want / kDeg, 0.1) << "open_jaw " << units;
}

INSTANTIATE_TEST_SUITE_P(Units, SimulateJaw, ::testing::Values(200, 400, 600));

}  // namespace
}  // namespace facectl
