// `facectl simulate` outputs: complete, documented and byte-identical from run to run.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/report/telemetry_csv.hpp"
#include "firmware-host/simulate/output_size.hpp"
#include "simulate_process.hpp"

namespace facectl {
namespace {

using testing::folder_contents;
using testing::run_facectl;
using testing::source_path;
using testing::TempDir;

std::vector<std::string> demo_args(const std::string& out) {
  return {"simulate",
          "--rig",
          source_path("config/rigs/default.yaml"),
          "--show",
          source_path("config/shows/demo.yaml"),
          "--out",
          out,
          "--duration",
          "4"};
}

TEST(Simulate, TwoRunsGiveByteIdenticalOutputs) {
  TempDir tmp;
  const auto a = run_facectl(demo_args(tmp / "a"), tmp / "a.log");
  const auto b = run_facectl(demo_args(tmp / "b"), tmp / "b.log");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto fa = folder_contents(tmp.path() / "a");
  const auto fb = folder_contents(tmp.path() / "b");
  ASSERT_GE(fa.size(), 5u);  // telemetry, summary x2, index, plots
  ASSERT_EQ(fa.size(), fb.size());
  for (const auto& [name, bytes] : fa) {
    ASSERT_TRUE(fb.count(name)) << name;
    EXPECT_TRUE(bytes == fb.at(name)) << name << " differs between runs";
  }
  // The bound `simulate` checks before writing (--max-output-mb) holds.
  std::uint64_t total = 0;
  for (const auto& [name, bytes] : fa) total += bytes.size();
  const ControllerModel m = load_config(default_config_path()).built.model;
  const std::uint64_t bound = simulate_output_bytes_at_most(m, 4.0, 10);
  EXPECT_LE(total, bound);
  // The output names no temporary path (it would differ between the two folders).
  for (const auto& [name, bytes] : fa) {
    EXPECT_EQ(bytes.find(tmp.path().string()), std::string::npos) << name;
  }
}

TEST(Simulate, TwoRenderedRunsGiveByteIdenticalFrames) {
  TempDir tmp;
  for (const char* out : {"a", "b"}) {
    auto args = demo_args(tmp / out);
    args.back() = "0.5";  // --duration
    args.push_back("--render");
    const auto r = run_facectl(args, tmp / "log");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const auto fa = folder_contents(tmp.path() / "a");
  ASSERT_TRUE(fa.count("frames/frame_00000.png"));
  ASSERT_TRUE(fa.count("frames/frame_00012.png"));  // 0.5 s at 25 fps: frames 0..12
  EXPECT_TRUE(fa == folder_contents(tmp.path() / "b"));
  EXPECT_NE(fa.at("index.html").find("src=\"frames/frame_00012.png\""), std::string::npos);
}

TEST(Simulate, WritesTheDocumentedFilesAtTheTelemetryRate) {
  TempDir tmp;
  auto args = demo_args(tmp / "out");
  args.insert(args.end(), {"--telemetry-rate", "50"});
  const auto r = run_facectl(args, tmp / "log");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const LoadedConfig cfg = load_config(default_config_path());
  const TelemetryTable t = read_telemetry_csv(tmp / "out/telemetry.csv");
  // 4 s at 50 Hz: rows at 0, 0.02, .., 4.0.
  EXPECT_EQ(t.rows.size(), 201u);
  const std::vector<double> time = t.numbers("time_s");
  EXPECT_DOUBLE_EQ(time.front(), 0.0);
  EXPECT_NEAR(time[1], 0.02, 1e-9);
  for (const auto& a : cfg.built.model.actuators) {
    EXPECT_GE(t.find("cmd." + a.name), 0) << a.name;
    EXPECT_GE(t.find("pos." + a.name), 0) << a.name;
    EXPECT_GE(t.find("lim." + a.name), 0) << a.name;
    EXPECT_TRUE(std::filesystem::exists(tmp.path() / "out/plots" / (a.name + ".svg"))) << a.name;
  }
  const auto summary = nlohmann::json::parse(testing::read_text(tmp.path() / "out/summary.json"));
  EXPECT_EQ(summary["result"], "ok");
  EXPECT_EQ(summary["actuators"].size(), cfg.built.model.actuators.size());
  EXPECT_EQ(summary["buses"].size(), cfg.built.model.buses.size());
  EXPECT_NEAR(summary["simulated_s"].get<double>(), 4.0, 1e-9);
  // The show moves the head: some actuator tracks with a non-zero error.
  double worst = 0.0;
  for (const auto& a : summary["actuators"])
    worst = std::max(worst, a["tracking_max"].get<double>());
  EXPECT_GT(worst, 0.0);
  const std::string html = testing::read_text(tmp.path() / "out/index.html");
  EXPECT_NE(html.find("href=\"telemetry.csv\""), std::string::npos);
  EXPECT_NE(html.find("src=\"plots/" + cfg.built.model.actuators[0].name + ".svg\""),
            std::string::npos);
  EXPECT_EQ(html.find("file:"), std::string::npos);  // relative links only
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / ".out.partial"));
}

}  // namespace
}  // namespace facectl
