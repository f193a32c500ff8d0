// --input's format detection from content: every real file we hold is
// recognised as what wrote it, and text that is none of them is not guessed.
#include "firmware-host/inputs/input_format.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

std::optional<InputFormat> detect_file(const std::string& path) {
  return detect_input_format(read_input_file(path, "input"));
}

TEST(InputFormat, RecognisesEveryRealFileByItsProducer) {
  const std::filesystem::path real(INPUT_REAL_FILES);
  // Rhubarb's XML export and MediaPipe's protobuf text are not formats we read.
  const struct {
    const char* folder;
    const char* extension;
    InputFormat format;
  } kinds[] = {
      {"live_link_face", ".csv", InputFormat::kLiveLinkFaceCsv},
      {"openface", ".csv", InputFormat::kOpenFaceCsv},
      {"rhubarb", ".json", InputFormat::kRhubarbJson},
      {"rhubarb", ".tsv", InputFormat::kRhubarbTsv},
      {"textgrid", ".TextGrid", InputFormat::kTextGrid},
      {"mediapipe", ".json", InputFormat::kMediapipeJson},
  };
  int seen = 0;
  for (const auto& k : kinds) {
    for (const auto& e : std::filesystem::directory_iterator(real / k.folder)) {
      if (e.path().extension() != k.extension) continue;
      const auto f = detect_file(e.path().string());
      ASSERT_TRUE(f.has_value()) << e.path();
      EXPECT_EQ(*f, k.format) << e.path() << " taken for " << input_format_name(*f);
      ++seen;
    }
  }
  EXPECT_EQ(seen, 12);
}

TEST(InputFormat, RecognisesTheShippedShowAndFapFiles) {
  const std::string config = std::string(FACECTL_SOURCE_DIR) + "/config/";
  EXPECT_EQ(detect_file(config + "shows/demo.yaml"), InputFormat::kShow);
  EXPECT_EQ(detect_file(config + "fap/demo.fap"), InputFormat::kFap);
}

TEST(InputFormat, RecognisesEachFormatsOwnOpening) {
  EXPECT_EQ(detect_input_format("0.00\tX\n0.05\tB\n"), InputFormat::kRhubarbTsv);
  EXPECT_EQ(detect_input_format("{\"metadata\": {}, \"mouthCues\": []}"),
            InputFormat::kRhubarbJson);
  EXPECT_EQ(detect_input_format("[{\"categoryName\": \"jawOpen\", \"score\": 0.1}]"),
            InputFormat::kMediapipeJson);
  EXPECT_EQ(detect_input_format("\xEF\xBB\xBF"
                                "File type = \"ooTextFile\"\n"),
            InputFormat::kTextGrid);
  EXPECT_EQ(detect_input_format(std::string("\xFF\xFE"
                                            "F\0i\0",
                                            6)),
            InputFormat::kTextGrid);
  EXPECT_EQ(detect_input_format("# a comment\n2.1 demo 25 10\n"), InputFormat::kFap);
  EXPECT_EQ(detect_input_format(std::string("RIFF\x24\0\0\0WAVEfmt ", 16)), InputFormat::kAudio);
  EXPECT_EQ(detect_input_format(std::string("fLaC\0\0\0\x22", 8)), InputFormat::kAudio);
  // A TextGrid in UTF-16 without its byte-order mark.
  EXPECT_EQ(detect_input_format(
                std::string("F\0i\0l\0e\0 \0t\0y\0p\0e\0 \0=\0 \0\"\0o\0o\0T\0e\0x\0t\0", 38)),
            InputFormat::kTextGrid);
}

TEST(InputFormat, AFapHeaderWithTabsIsNotTakenForRhubarb) {
  EXPECT_EQ(detect_input_format("2.1\tAlice\t25\t100\n"), InputFormat::kFap);
  EXPECT_EQ(detect_input_format("#\tBy me\n2.1 clip 25 1\n"), InputFormat::kFap);
  EXPECT_FALSE(detect_input_format("Alice\tBob\n").has_value());
}

TEST(InputFormat, DoesNotGuessAtOtherText) {
  for (const char* text : {"", "hello\n", "{\"a\": 1}", "1,2,3\n", "0.00\tZ\n", "2.2 x 25 1\n",
                           "RIFF1234AVI ", "RIFF", "RIFF123"}) {
    EXPECT_FALSE(detect_input_format(text).has_value()) << text;
  }
}

TEST(InputFormat, NamesRoundTrip) {
  for (const char* n : {"show", "fap", "live_link_face", "mediapipe", "openface", "rhubarb_json",
                        "rhubarb_tsv", "textgrid", "audio", "audio_phonemes"}) {
    const auto f = parse_input_format(n);
    ASSERT_TRUE(f.has_value()) << n;
    EXPECT_STREQ(input_format_name(*f), n);
  }
  EXPECT_FALSE(parse_input_format("csv").has_value());
}

}  // namespace
}  // namespace facectl
