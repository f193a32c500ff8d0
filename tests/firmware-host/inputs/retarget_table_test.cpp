// The head's FACS/ARKit retargeting table (config/heads/default/retarget.yaml):
// what it loads, how it sums, and every refusal naming file:line.
#include "firmware-host/inputs/retarget_table.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "default_retarget.hpp"
#include "firmware-host/config/config_location.hpp"
#include "firmware-host/config/runtime_config.hpp"

namespace facectl {
namespace {

const HeadConfig& head() {
  return testing::default_head_config();
}
const RetargetTable& table() {
  return testing::default_retarget();
}
const std::string& kHeadDir = testing::kDefaultHeadDir;

double signal(const std::array<double, kMaxFaceSignals>& pose, std::string_view name) {
  return pose[*head().layout.find(name)];
}

// Per process: ctest runs tests in parallel.
const std::string kBroken = (std::filesystem::temp_directory_path() /
                             ("facectl_retarget_test_" + std::to_string(getpid()) + ".yaml"))
                                .string();

// Loads a copy of the shipped table with `from` replaced by `to`; returns the
// error, and in `line` the line the replacement is on.
std::string load_error(const std::string& from, const std::string& to, int& line,
                       const HeadConfig& h = head()) {
  std::ifstream in(kHeadDir + "/retarget.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return "";
  line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  text.replace(at, from.size(), to);
  std::ofstream(kBroken) << text;
  try {
    RetargetTable::load(kBroken, h);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "loaded";
}

void expect_refused(const std::string& from, const std::string& to, const std::string& what) {
  int line = 0;
  const std::string e = load_error(from, to, line);
  EXPECT_NE(e.find(kBroken + ":" + std::to_string(line) + ":"), std::string::npos) << e;
  EXPECT_NE(e.find(what), std::string::npos) << e;
}

TEST(RetargetTable, TheShippedTableMapsOrListsEveryBlendshape) {
  int mapped = 0;
  for (std::size_t k = 0; k < kArkitCount; ++k) {
    const bool listed = table().unmapped().count(std::string(kArkitNames[k])) > 0;
    EXPECT_NE(table().has_arkit(k), listed) << kArkitNames[k];
    mapped += table().has_arkit(k);
  }
  EXPECT_EQ(mapped, 46);  // cheekPuff, tongueOut, eyeWide and mouthDimple x2 are unmapped
  for (int au : {1, 2, 4, 6, 7, 9, 10, 12, 15, 17, 20, 23, 25, 26, 45}) {
    EXPECT_TRUE(table().has_action_unit(au)) << "AU" << au << " (OpenFace's)";
  }
  EXPECT_EQ(table().unmapped().count("AU05"), 1u);
}

TEST(RetargetTable, ASidedBlendshapeMovesItsSideAndHalfTheMidline) {
  std::array<double, kArkitCount> w{};
  w[*find_arkit("mouthSmileLeft")] = 1.0;
  std::array<double, kMaxFaceSignals> pose{};
  table().add_arkit(w, pose);
  EXPECT_DOUBLE_EQ(signal(pose, "zygomaticus_major_l"), 0.9);  // AU12 at E
  EXPECT_DOUBLE_EQ(signal(pose, "zygomaticus_major_r"), 0.0);

  w = {};
  w[*find_arkit("mouthPressLeft")] = 1.0;
  w[*find_arkit("mouthPressRight")] = 1.0;
  pose = {};
  table().add_arkit(w, pose);
  EXPECT_NEAR(signal(pose, "orbicularis_oris"), 0.7, 1e-12);  // AU24 whole
}

TEST(RetargetTable, JawOpenAndBlinkReachTheirLimits) {
  std::array<double, kArkitCount> w{};
  w[*find_arkit("jawOpen")] = 0.5;
  w[*find_arkit("eyeBlinkRight")] = 1.0;
  std::array<double, kMaxFaceSignals> pose{};
  EXPECT_EQ(table().add_arkit(w, pose), 0);
  EXPECT_NEAR(signal(pose, "jaw_pitch"), 9.0 * M_PI / 180, 1e-12);
  EXPECT_DOUBLE_EQ(signal(pose, "eyelid_closure_r"), 1.0);
  EXPECT_DOUBLE_EQ(signal(pose, "eyelid_closure_l"), 0.0);
}

TEST(RetargetTable, SumsAreClampedToTheSignalDomainAndCounted) {
  std::array<double, RetargetTable::kMaxActionUnit + 1> a{};
  a[18] = 5;  // orbicularis oris 0.8
  a[28] = 5;  // and 1.0 more
  std::array<double, kMaxFaceSignals> pose{};
  EXPECT_EQ(table().add_action_units(a, pose), 1);
  EXPECT_DOUBLE_EQ(signal(pose, "orbicularis_oris"), 1.0);
}

TEST(RetargetTable, ActionUnitIntensityIsOutOfFive) {
  std::array<double, RetargetTable::kMaxActionUnit + 1> a{};
  a[12] = 2.5;
  std::array<double, kMaxFaceSignals> pose{};
  table().add_action_units(a, pose);
  EXPECT_DOUBLE_EQ(signal(pose, "zygomaticus_major_l"), 0.45);  // half of AU12's 0.9
}

TEST(RetargetTable, RefusesWhatItCannotUseNamingTheLine) {
  expect_refused("    AU13:", "    AUX13:", "expected an action unit key");
  expect_refused("mouthSmileLeft: {", "mouthSmileLeftt: {", "ARKit's 52 blendshape names");
  expect_refused("{ facs: { AU12: 1 }, side: left }", "{ facs: { AU12: 1 }, side: up }",
                 "expected left or right");
  expect_refused("jawOpen: { facs: { AU27: 1 } }", "jawOpen: { facs: { AU32: 1 } }",
                 "an action unit that action_units maps");
  expect_refused("zygomaticus_major_l: 0.9, zygomaticus_major_r: 0.9",
                 "zygomaticus_major_l: 0.9, zygomatic_r: 0.9", "unknown muscle");
  expect_refused("    AU39: no nostril", "    AU12: no nostril", "that action_units does not map");
}

TEST(RetargetTable, ABlendshapeNeitherMappedNorUnmappedIsNamed) {
  int line = 0;
  const std::string e = load_error("    tongueOut: no tongue (AU19)\n", "", line);
  EXPECT_NE(e.find("none for tongueOut"), std::string::npos) << e;
  EXPECT_NE(e.find(kBroken + ":"), std::string::npos) << e;
}

TEST(RetargetTable, TheHeadsFacsListsMustAgreeBothWays) {
  int line = 0;
  // head.yaml says mentalis serves AU17; the table's AU17 no longer moves it.
  std::string e = load_error("AU17: { muscles: { mentalis_l: 1, mentalis_r: 1 } }",
                             "AU17: { muscles: { mentalis_r: 1 } }", line);
  EXPECT_NE(e.find("head.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("muscle mentalis_l serves AU17"), std::string::npos) << e;
  // The table's AU13 contracts risorius, whose facs list says 20 only.
  e = load_error("AU13: { muscles: { levator_anguli_oris_l: 1,",
                 "AU13: { muscles: { risorius_l: 0.2, levator_anguli_oris_l: 1,", line);
  EXPECT_NE(e.find(kBroken + ":" + std::to_string(line) + ":"), std::string::npos) << e;
  EXPECT_NE(e.find("AU13 contracts risorius_l"), std::string::npos) << e;
}

}  // namespace
}  // namespace facectl
