// A head that faults in simulation: exit 1, the outputs written all the same,
// the fault in the summary, its span in the plots.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "simulate_process.hpp"

namespace facectl {
namespace {

// The shipped rig with neck_pan's time-at-extreme budget cut to 2 s over a
// 30° band, and a show that holds the neck at 50° for 5.5 s: its overload
// protection trips (docs/CONFIG.md, "Plant") and the controller faults.
TEST(SimulateFault, AnOverloadedServoFaultsTheHeadAndExitsOne) {
  testing::TempDir tmp;
  std::string rig = testing::read_text(testing::source_path("config/rigs/default.yaml"));
  const auto pan = rig.find("    - name: neck_pan\n");
  const auto at = rig.find("noise_deg: 0.05, backlash_deg: 0.05 }", pan);
  ASSERT_NE(pan, std::string::npos) << "the shipped rig has no neck_pan";
  ASSERT_LT(at, rig.find("    - name: ", pan + 1)) << "the shipped rig's neck_pan plant changed";
  rig.replace(at, std::string("noise_deg: 0.05, backlash_deg: 0.05 }").size(),
              "noise_deg: 0.05, backlash_deg: 0.05, extreme_band_deg: 30, extreme_budget_s: 2 }");
  testing::write_text(tmp / "rig.yaml", rig);
  testing::write_text(tmp / "pan.yaml",
                      "show:\n  name: pan_and_hold\n  keyframes:\n"
                      "    - { t: 0.0, expression: neutral }\n"
                      "    - { t: 0.5, rigid: { neck_pan_deg: 50 } }\n"
                      "    - { t: 6.0, rigid: { neck_pan_deg: 50 } }\n");
  const auto r = testing::run_facectl(
      {"simulate", "--rig", tmp / "rig.yaml", "--show", tmp / "pan.yaml", "--out", tmp / "out"},
      tmp / "log");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto s = nlohmann::json::parse(testing::read_text(tmp.path() / "out/summary.json"));
  EXPECT_EQ(s["result"], "faulted");
  bool fault_span = false;
  for (const auto& st : s["states"]) fault_span = fault_span || st["state"] == "FAULT";
  EXPECT_TRUE(fault_span);
  for (const auto& a : s["actuators"]) {
    if (a["name"] != "neck_pan") continue;
    EXPECT_TRUE(a["plant"]["over_budget"].get<bool>());
    // The budget of 2 s starts once the neck is inside the band, a little after 0.5 s.
    EXPECT_GT(a["plant"]["over_budget_at_s"].get<double>(), 2.0);
    EXPECT_LT(a["plant"]["over_budget_at_s"].get<double>(), 3.0);
  }
  EXPECT_NE(testing::read_text(tmp.path() / "out/plots/neck_pan.svg").find(">FAULT</text>"),
            std::string::npos);
  EXPECT_NE(testing::read_text(tmp.path() / "out/index.html").find("neck_pan: over its"),
            std::string::npos);
}

}  // namespace
}  // namespace facectl
