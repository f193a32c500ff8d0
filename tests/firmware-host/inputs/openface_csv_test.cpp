// OpenFace 2.x CSV: its own output (inputs/real/openface), frames the tracker
// lost held rather than played, and broken files refused at their line.
#include "firmware-host/inputs/openface_csv.hpp"

#include <gtest/gtest.h>

#include "default_retarget.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

const HeadConfig& head() {
  return testing::default_head_config();
}
const RetargetTable& table() {
  return testing::default_retarget();
}

// OpenFace's layout in small: header with ", ", rows with ",".
const std::string kHeader =
    "frame, timestamp, confidence, success, AU12_r, AU45_r, AU12_c, AU28_c\n";

std::string error_of(const std::string& text) {
  try {
    parse_openface_csv(text, "o.csv");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "parsed";
}

TEST(OpenFaceCsv, ReadsOpenFacesOwnOutput) {
  const std::string text = read_input_file(
      std::string(INPUT_REAL_FILES) + "/openface/OpenFace_Test.first3lines.csv", "CSV");
  ASSERT_TRUE(looks_like_openface_csv(text));
  const OpenFaceCapture c = parse_openface_csv(text, "OpenFace_Test");
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_TRUE(c.frames[0].tracked);  // confidence 0.883333, success 1
  EXPECT_NEAR(c.frames[1].t, 0.001, 1e-12);
}

TEST(OpenFaceCsv, IntensitiesDriveTheTableAndPresenceOnlyAusPlayAtC) {
  const OpenFaceCapture c = parse_openface_csv(kHeader + "1,0.0,0.98,1,2.5,0,1,1\n", "o.csv");
  EXPECT_DOUBLE_EQ(c.frames[0].intensity[12], 2.5);  // AU12_c ignored: AU12_r is there
  EXPECT_DOUBLE_EQ(c.frames[0].intensity[28], kPresenceOnlyIntensity);
  std::vector<std::string> notes;
  const PoseTrack t = openface_pose_track(c, table(), head().layout, head().neutral, notes);
  EXPECT_DOUBLE_EQ(t.pose(0)[*head().layout.find("zygomaticus_major_l")], 0.45);  // 2.5/5 of 0.9
}

TEST(OpenFaceCsv, LostFramesAreHeldNotPlayed) {
  const OpenFaceCapture c = parse_openface_csv(kHeader +
                                                   "1,0.0,0.98,1,5,0,1,0\n"
                                                   "2,0.1,0.98,0,0,0,0,0\n"  // lost
                                                   "3,0.2,0.30,1,0,0,0,0\n"  // unsure
                                                   "4,0.3,0.98,1,0,0,0,0\n",
                                               "o.csv");
  EXPECT_FALSE(c.frames[1].tracked);
  EXPECT_FALSE(c.frames[2].tracked);
  ASSERT_EQ(c.notes.size(), 1u);
  std::vector<std::string> notes;
  const PoseTrack t = openface_pose_track(c, table(), head().layout, head().neutral, notes);
  const std::size_t smile = *head().layout.find("zygomaticus_major_l");
  std::array<double, kMaxFaceSignals> p{};
  t.evaluate(0.15, p);
  EXPECT_DOUBLE_EQ(p[smile], 0.9);  // still the last tracked smile (AU12 at 5)
  t.evaluate(0.2, p);
  EXPECT_DOUBLE_EQ(p[smile], 0.9);
  t.evaluate(0.3, p);
  EXPECT_DOUBLE_EQ(p[smile], 0.0);
}

TEST(OpenFaceCsv, RefusesBrokenFilesAtTheirLine) {
  EXPECT_NE(error_of("").find("o.csv:1: expected an OpenFace CSV header"), std::string::npos);
  EXPECT_NE(error_of("frame, AU12_r\n").find("o.csv:1: expected OpenFace's timestamp"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "1,0.0,0.98,1,2.5,0\n").find("o.csv:2: expected 8 fields"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "1,0.0,0.98,1,x,0,1,1\n")
                .find("o.csv:2: expected an AU intensity as a number"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "1,0.0,0.98,1,9,0,1,1\n")
                .find("o.csv:2: expected an AU intensity in 0..5"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "1,0.0,0.98,2,1,0,1,1\n").find("o.csv:2: expected success 0 or 1"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "1,0.0,0.98,1,1,0,1,0.5\n")
                .find("o.csv:2: expected an AU presence 0 or 1"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "1,0.1,0.98,1,1,0,1,0\n2,0.1,0.98,1,1,0,1,0\n")
                .find("o.csv:3: expected timestamps that increase"),
            std::string::npos);
}

}  // namespace
}  // namespace facectl
