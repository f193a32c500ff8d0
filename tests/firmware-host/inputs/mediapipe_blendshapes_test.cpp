// MediaPipe face landmarker blendshapes saved as JSON, in the shapes its
// APIs print (categoryName / category_name), and broken files named by path.
#include "firmware-host/inputs/mediapipe_blendshapes.hpp"

#include <gtest/gtest.h>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_mediapipe_blendshapes(text, "m.json");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "parsed";
}

TEST(MediapipeBlendshapes, ReadsOneFrameOfCategoriesAsTheJsApiWritesIt) {
  const ArkitCapture c = parse_mediapipe_blendshapes(
      R"([{"index": 0, "score": 0.00001, "categoryName": "_neutral", "displayName": ""},
          {"index": 25, "score": 0.62, "categoryName": "jawOpen", "displayName": ""}])",
      "m.json");
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_DOUBLE_EQ(c.frames[0].weights[*find_arkit("jawOpen")], 0.62);
  EXPECT_TRUE(c.notes.empty());  // _neutral is no motion, not an unknown
}

TEST(MediapipeBlendshapes, ReadsFramesWithTimesAndTheFirstFace) {
  const ArkitCapture c = parse_mediapipe_blendshapes(
      R"({"frames": [
           {"timestamp_ms": 1000, "face_blendshapes": [[{"category_name": "mouthSmileLeft", "score": 0.5}],
                                                       [{"category_name": "mouthSmileLeft", "score": 0.9}]]},
           {"timestamp_ms": 1033, "face_blendshapes": [[{"category_name": "mouthSmileLeft", "score": 0.7}]]}]})",
      "m.json");
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(c.frames[0].weights[*find_arkit("mouthSmileLeft")], 0.5);
  EXPECT_NEAR(c.frames[1].t, 0.033, 1e-12);
}

TEST(MediapipeBlendshapes, FramesWithoutTimesAreAThirtiethApart) {
  const ArkitCapture c = parse_mediapipe_blendshapes(
      R"([{"jawOpen": 0.1}, {"jawOpen": 0.2}, {"jawOpen": 0.3}])", "m.json");
  ASSERT_EQ(c.frames.size(), 3u);
  EXPECT_NEAR(c.frames[2].t, 2.0 / 30.0, 1e-12);
}

TEST(MediapipeBlendshapes, ReadsTheLabelersFilesAndNamesTheirPaths) {
  const std::string dir = std::string(INPUT_REAL_FILES) + "/mediapipe/";
  for (const char* name :
       {"mediapipe-labeler_blendshapes.json", "mediapipe-labeler_image.jpg_blendshapes.json"}) {
    const ArkitCapture c = parse_mediapipe_blendshapes(read_input_file(dir + name, "JSON"), name);
    ASSERT_EQ(c.frames.size(), 1u) << name;
    // Both hold the same face: brows down (0.815 and 0.838).
    EXPECT_GT(c.frames[0].weights[*find_arkit("browDownLeft")], 0.8) << name;
    EXPECT_TRUE(c.notes.empty()) << name << ": " << c.notes.front();
  }
  std::string text = read_input_file(dir + "mediapipe-labeler_blendshapes.json", "JSON");
  text.replace(text.find("0.8152358531951904"), 18, "\"high\"");
  EXPECT_NE(error_of(text).find("m.json: people[0][1].score: expected a score"), std::string::npos)
      << error_of(text);
}

TEST(MediapipeBlendshapes, FramesWithoutAFaceAreDroppedAndCounted) {
  const ArkitCapture c = parse_mediapipe_blendshapes(
      R"({"frames": [{"t": 0, "people": []}, {"t": 0.1, "people": [[{"name": "jawOpen", "score": 0.5}]]}]})",
      "m.json");
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_NEAR(c.frames[0].t, 0.1, 1e-12);
  ASSERT_EQ(c.notes.size(), 1u);
  EXPECT_EQ(c.notes[0], "dropped 1 frames without a face");
  EXPECT_NE(error_of(R"({"people": []})").find("expected at least one frame with a face"),
            std::string::npos);
}

TEST(MediapipeBlendshapes, DeepNestingIsRefusedBeforeItIsParsed) {
  // 100 000 ['s: nlohmann's dump() and copies would recurse that deep.
  EXPECT_NE(error_of(std::string(100000, '[')).find("m.json: expected JSON nested at most 16 deep"),
            std::string::npos);
  EXPECT_NE(error_of("{\"jawOpen\": " + std::string(20, '[') + std::string(20, ']') + "}")
                .find("nested at most 16 deep"),
            std::string::npos);
  // Brackets inside strings are not nesting.
  EXPECT_EQ(error_of("[{\"categoryName\": \"[[[[[[[[[[[[[[[[[[[[\", \"score\": 0.1}]"), "parsed");
}

TEST(MediapipeBlendshapes, RefusesBrokenFilesByPath) {
  EXPECT_EQ(error_of("[{\"jawOpen\": 0.1}"),
            "m.json:1: expected MediaPipe blendshapes JSON, found text that is not JSON");
  // nlohmann throws out_of_range, not parse_error, for this (a fuzz finding).
  EXPECT_EQ(error_of("[\n{\"jawOpen\": 1e999}]"),
            "m.json:2: expected numbers a double can hold, found '1e999'");
  EXPECT_NE(error_of("[]").find("expected a list of frames"), std::string::npos);
  EXPECT_NE(error_of(R"([{"jawOpen": "x"}])").find("m.json: [0].jawOpen: expected a score"),
            std::string::npos);
  EXPECT_NE(error_of(R"([{"jawOpen": 3}])").find("m.json: [0].jawOpen: expected a score in 0..1"),
            std::string::npos);
  EXPECT_NE(error_of(R"([[{"categoryName": "jawOpen"}]])").find("m.json: [0][0]: expected a score"),
            std::string::npos);
  EXPECT_NE(error_of(R"([{"t": 1, "blendshapes": []}, {"t": 0.5, "blendshapes": []}])")
                .find("m.json: [1]: expected times that increase"),
            std::string::npos);
}

}  // namespace
}  // namespace facectl
