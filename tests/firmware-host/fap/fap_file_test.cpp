#include "firmware-host/fap/fap_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace facectl {
namespace {

std::string file(const std::string& name) {
  return std::string(FAP_TEST_FILES) + "/" + name;
}

TEST(FapFile, GoodFileParsesEveryField) {
  const FapSequence s = load_fap_file(file("good.fap"));
  EXPECT_EQ(s.header.version, "2.1");
  EXPECT_EQ(s.header.name, "good_clip");
  EXPECT_DOUBLE_EQ(s.header.frame_rate, 25.0);
  ASSERT_EQ(s.frames.size(), 3u);
  const FapFrame& f0 = s.frames[0];
  EXPECT_EQ(f0.number, 0);
  EXPECT_EQ(f0.mask.count(), 5u);
  EXPECT_EQ(f0.viseme.select1, 1);
  EXPECT_EQ(f0.viseme.select2, 10);
  EXPECT_EQ(f0.viseme.blend, 32);
  EXPECT_EQ(f0.expression.select1, 1);
  EXPECT_EQ(f0.expression.intensity1, 63);
  EXPECT_DOUBLE_EQ(f0.values[2], 200.0);           // FAP 3
  EXPECT_DOUBLE_EQ(f0.values[11], -35.5);          // FAP 12
  EXPECT_DOUBLE_EQ(f0.values[47], 1000.0);         // FAP 48
  EXPECT_DOUBLE_EQ(s.frames[1].values[2], 400.0);  // "+400", CRLF line ends
  EXPECT_EQ(s.frames[2].number, 4);
  EXPECT_DOUBLE_EQ(s.frames[2].values[14], -120.25);
  EXPECT_DOUBLE_EQ(s.time_of(s.frames[2]), 4.0 / 25.0);
  EXPECT_TRUE(s.used[2] && s.used[11] && s.used[14] && s.used[47]);
  EXPECT_FALSE(s.used[3]);
}

TEST(FapFile, RoundTripThroughTheWriter) {
  const FapSequence a = load_fap_file(file("good.fap"));
  const std::string text = format_fap_text(a);
  const FapSequence b = parse_fap_text(text, "written");
  ASSERT_EQ(a.frames.size(), b.frames.size());
  EXPECT_EQ(a.header.name, b.header.name);
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    EXPECT_EQ(a.frames[k].number, b.frames[k].number);
    EXPECT_EQ(a.frames[k].mask, b.frames[k].mask);
    EXPECT_EQ(a.frames[k].values, b.frames[k].values);
    EXPECT_EQ(a.frames[k].viseme.blend, b.frames[k].viseme.blend);
    EXPECT_EQ(a.frames[k].expression.intensity1, b.frames[k].expression.intensity1);
  }
  EXPECT_EQ(format_fap_text(b), text);
}

TEST(FapFile, TheShippedDemoParses) {
  const FapSequence s = load_fap_file(std::string(FACECTL_SOURCE_DIR) + "/config/fap/demo.fap");
  EXPECT_EQ(s.frames.size(), static_cast<std::size_t>(s.header.frame_count));
  EXPECT_GT(s.frames.size(), 50u);
}

struct Malformed {
  const char* file;
  int line;
  std::vector<const char*> fragments;  // the expected and found parts of the message
};

class MalformedFapFile : public ::testing::TestWithParam<Malformed> {};

TEST_P(MalformedFapFile, GetsALineNumberedError) {
  const Malformed& m = GetParam();
  const std::string path = file(m.file);
  try {
    (void)load_fap_file(path);
    FAIL() << m.file << " parsed";
  } catch (const FapFormatError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.line(), m.line) << what;
    EXPECT_EQ(what.rfind(path + ":" + std::to_string(m.line) + ":", 0), 0u) << what;
    EXPECT_NE(what.find("expected"), std::string::npos) << what;
    EXPECT_NE(what.find("found"), std::string::npos) << what;
    for (const char* f : m.fragments) EXPECT_NE(what.find(f), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedFapFile,
    ::testing::Values(
        Malformed{"bad_version.fap", 1, {"version 2.0 or 2.1", "'1.0'"}},
        Malformed{"bad_header_fields.fap", 1, {"frame_rate frame_count", "3 fields"}},
        Malformed{"bad_frame_rate.fap", 1, {"frame rate > 0", "'zero'"}},
        Malformed{"mask_count.fap", 2, {"68 entries", "67 entries"}},
        Malformed{"mask_value.fap", 2, {"0 or 1 as mask entry 12", "raise_l_cornerlip", "'2'"}},
        Malformed{"value_count.fap", 5, {"3 fields", "mask at line 4", "2 fields"}},
        Malformed{"non_numeric.fap", 4, {"a number as the value of FAP 12", "'abc'"}},
        Malformed{"non_finite.fap", 5, {"a finite number", "FAP 3 open_jaw", "'inf'"}},
        Malformed{"out_of_order.fap", 7, {"greater than the previous frame's 2", "found 1"}},
        Malformed{"truncated_frames.fap", 6, {"5 frames", "after 2 (truncated)"}},
        Malformed{"truncated_values.fap", 5, {"values line", "mask is at line 4", "truncated"}},
        Malformed{"too_many_frames.fap", 5, {"declares 1", "frame 1 beyond"}},
        Malformed{"viseme_range.fap", 3, {"viseme_select1", "0..14", "'15'"}},
        Malformed{"empty.fap", 2, {"a header", "end of the input"}},
        Malformed{
            "beyond_a_day.fap",
            6,
            {"at most 86400 s in (frame 2160000 at 25 fps)", "found frame 9000000000000000000"}},
        Malformed{"slow_rate.fap", 6, {"(frame 0 at 1e-300 fps)", "found frame 1"}}),
    [](const ::testing::TestParamInfo<Malformed>& p) {
      std::string n = p.param.file;
      return n.substr(0, n.find('.'));
    });

TEST(FapFile, MissingFileIsAnError) {
  EXPECT_THROW((void)load_fap_file(file("no_such.fap")), ConfigError);
}

// Issue 21: a directory read as an empty file ("expected a header"), and a
// FIFO or a device was read until it ended, or memory did.
TEST(FapFile, OnlyARegularFileWithinTheBoundIsRead) {
  const std::string dir = FAP_TEST_FILES;
  try {
    (void)load_fap_file(dir);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, expected a FAP file");
  }
  try {
    (void)load_fap_file("/dev/zero");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/zero: is not a regular file, expected a FAP file");
  }
}

}  // namespace
}  // namespace facectl
