// Live Link Face CSV: the app's own recordings (inputs/real/live_link_face,
// written by other people's phones) and broken files, each refused at its line.
#include "firmware-host/inputs/live_link_face_csv.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

const std::string kDir = std::string(INPUT_REAL_FILES) + "/live_link_face/";

std::string header() {
  std::string h = "Timecode,BlendShapeCount";
  for (auto n : kArkitNames) {
    std::string s(n);
    s[0] = static_cast<char>(std::toupper(s[0]));  // the app capitalises
    h += "," + s;
  }
  return h +
         ",HeadYaw,HeadPitch,HeadRoll,LeftEyeYaw,LeftEyePitch,LeftEyeRoll,RightEyeYaw,"
         "RightEyePitch,RightEyeRoll\n";
}

// A row: timecode, count, 52 weights (jawOpen = jaw), 9 rotations (head yaw = yaw).
std::string row(const std::string& tc, double jaw = 0.0, double yaw = 0.0, int count = 61) {
  std::string r = tc + "," + std::to_string(count);
  for (auto n : kArkitNames) r += n == "jawOpen" ? "," + std::to_string(jaw) : ",0.0000000000";
  r += "," + std::to_string(yaw);
  for (int i = 0; i < 8; ++i) r += ",0.0";
  return r + "\n";
}

std::string error_of(const std::string& text) {
  try {
    parse_live_link_face_csv(text, "f.csv");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "parsed";
}

TEST(LiveLinkFaceCsv, ReadsTheAppsRecordings) {
  for (const char* name :
       {"MySlate_3_Jason_Millers_iPhone.first7lines.csv", "S07-001.first9lines.csv"}) {
    const std::string text = read_input_file(kDir + name, "CSV");
    ASSERT_TRUE(looks_like_live_link_face_csv(text)) << name;
    const ArkitCapture c = parse_live_link_face_csv(text, name);
    EXPECT_GE(c.frames.size(), 6u) << name;
    EXPECT_TRUE(c.frames.front().has_head) << name;
    EXPECT_DOUBLE_EQ(c.frames.front().t, 0.0);
  }
}

TEST(LiveLinkFaceCsv, TakesTheValuesFromTheirNamedColumns) {
  // S07-001 line 2: 12:27:47:47.169, EyeLookOutLeft 0.1421131641, EyeLookUpLeft 0.4678646922.
  const ArkitCapture c =
      parse_live_link_face_csv(read_input_file(kDir + "S07-001.first9lines.csv", "CSV"), "S07");
  EXPECT_DOUBLE_EQ(c.frames[0].weights[*find_arkit("eyeLookOutLeft")], 0.1421131641);
  EXPECT_DOUBLE_EQ(c.frames[0].weights[*find_arkit("eyeLookUpLeft")], 0.4678646922);
  // Its timecode steps 2 frames a row at 60 fps: 1/30 s.
  EXPECT_NEAR(c.frames[1].t, 2.0 / 60.0, 1e-9);
  // Across 12:27:47:59.167 -> 12:27:48:01.167 too.
  EXPECT_NEAR(c.frames[7].t - c.frames[6].t, 2.0 / 60.0, 1e-9);
}

TEST(LiveLinkFaceCsv, ColumnsAreFoundByNameInAnyOrderAndCase) {
  // The header and rows reversed, the names in lower case.
  auto reversed = [](const std::string& line) {
    std::vector<std::string> f;
    const std::string body = line.substr(0, line.size() - 1);  // outlives the views
    for (auto v : split_fields(body, ',')) f.emplace_back(v);
    std::string out;
    for (auto it = f.rbegin(); it != f.rend(); ++it) out += (out.empty() ? "" : ",") + *it;
    return out + "\n";
  };
  std::string h = header();
  for (char& ch : h) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const std::string text = reversed(h) + reversed(row("00:00:01:00.000", 0.25, 0.1)) +
                           reversed(row("00:00:01:01.000", 0.5, 0.2));
  const ArkitCapture c = parse_live_link_face_csv(text, "f.csv");
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(c.frames[1].weights[*find_arkit("jawOpen")], 0.5);
  EXPECT_DOUBLE_EQ(c.frames[1].weights[*find_arkit("eyeBlinkLeft")], 0.0);
  EXPECT_DOUBLE_EQ(c.frames[1].head_yaw, 0.2);
  EXPECT_NEAR(c.frames[1].t, 1.0 / 60.0, 1e-12);
}

TEST(LiveLinkFaceCsv, ATakeAcrossMidnightKeepsCounting) {
  const ArkitCapture c = parse_live_link_face_csv(
      header() + row("23:59:59:58.000") + row("23:59:59:59.000") + row("00:00:00:00.000"), "f.csv");
  ASSERT_EQ(c.frames.size(), 3u);
  EXPECT_NEAR(c.frames[2].t, 2.0 / 60.0, 1e-9);
}

TEST(LiveLinkFaceCsv, ARepeatedTimecodeIsARepeatWhereverItFalls) {
  // Far from the first row, where (t - t0) + t0 is not t again in doubles.
  for (const auto& [first, later] : {std::pair{"00:00:00:07.867", "00:00:01:07.868"},
                                     std::pair{"02:14:20:03.778", "09:00:35:53.050"}}) {
    const ArkitCapture c =
        parse_live_link_face_csv(header() + row(first) + row(later) + row(later), "f.csv");
    EXPECT_EQ(c.frames.size(), 2u) << later;
  }
}

TEST(LiveLinkFaceCsv, ATimecodeThatRollsOverShowsItsRate) {
  std::string text = header();
  for (int s = 1; s <= 2; ++s) {
    for (int f = 0; f < 30; ++f) {
      char tc[32];
      std::snprintf(tc, sizeof tc, "00:00:%02d:%02d.000", s, f);
      text += row(tc);
    }
  }
  const ArkitCapture c = parse_live_link_face_csv(text, "f.csv");
  EXPECT_NEAR(c.frames.back().t, 59.0 / 30.0, 1e-9);
}

TEST(LiveLinkFaceCsv, DropsRowsWithoutAFaceAndRepeatedTimecodesAndSaysSo) {
  const std::string text = header() + row("00:00:01:00.000") + row("00:00:01:01.000", 0, 0, 0) +
                           row("00:00:01:01.000") + row("00:00:01:01.000") + row("00:00:01:02.000");
  const ArkitCapture c = parse_live_link_face_csv(text, "f.csv");
  EXPECT_EQ(c.frames.size(), 3u);
  std::string notes;
  for (const auto& n : c.notes) notes += n + "\n";
  EXPECT_NE(notes.find("dropped 1 rows without a face"), std::string::npos) << notes;
  EXPECT_NE(notes.find("dropped 1 rows repeating"), std::string::npos) << notes;
}

TEST(LiveLinkFaceCsv, RefusesBrokenFilesAtTheirLine) {
  const std::string h = header();
  EXPECT_NE(error_of("").find("f.csv:1: expected a header"), std::string::npos);
  EXPECT_NE(error_of("Timecode,BlendShapeCount,EyeBlinkLeft\n").find("f.csv:1: expected all 52"),
            std::string::npos);
  EXPECT_NE(error_of(h + row("00:00:01:00.000") + "00:00:01:01.000,61,0.1\n")
                .find("f.csv:3: expected 63 fields"),
            std::string::npos);
  EXPECT_NE(error_of(h + row("00:00:01:00.000") + row("00:00:1:xx.000"))
                .find("f.csv:3: expected a timecode"),
            std::string::npos);
  EXPECT_NE(error_of(h + row("00:00:01:00.000", 7.0)).find("f.csv:2: expected jawOpen in 0..1"),
            std::string::npos);
  std::string nan_row = row("00:00:01:00.000");
  nan_row.replace(nan_row.find(",0.0000000000"), 13, ",nan");
  EXPECT_NE(error_of(h + nan_row).find("f.csv:2: expected eyeBlinkLeft as a number"),
            std::string::npos);
  EXPECT_NE(error_of(h + row("00:00:01:00.000", 0, 9.0)).find("f.csv:2: expected a head rotation"),
            std::string::npos);
  EXPECT_NE(error_of(h + row("00:00:02:00.000") + row("00:00:01:00.000"))
                .find("f.csv:3: expected timecodes that increase"),
            std::string::npos);
  EXPECT_NE(
      error_of(h + row("00:00:01:00.000", 0, 0, 0)).find("expected at least one frame with a face"),
      std::string::npos);
}

}  // namespace
}  // namespace facectl
