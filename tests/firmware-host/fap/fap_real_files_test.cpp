// FAP files as other players' tools write them: Xface's samples as its
// exml2fap wrote them (files/real/xface/, SOURCE.md names their origin and
// licence), and files written here in Greta's and VREng's layouts (their
// writers' code is cited in docs/FAP.md). Each check compares a value with
// the file's text, quoted by its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "firmware-host/fap/fap_file.hpp"

namespace facectl {
namespace {

std::string file(const std::string& name) {
  return std::string(FAP_TEST_FILES) + "/" + name;
}

TEST(FapRealFiles, EveryOneParses) {
  std::vector<std::string> paths;
  for (const auto& e : std::filesystem::recursive_directory_iterator(file("real"))) {
    if (e.path().extension() == ".fap") paths.push_back(e.path().string());
  }
  std::sort(paths.begin(), paths.end());
  EXPECT_GE(paths.size(), 2u);
  for (const std::string& p : paths) {
    EXPECT_NO_THROW({
      const FapSequence s = load_fap_file(p);
      EXPECT_EQ(static_cast<long>(s.frames.size()), s.header.frame_count) << p;
    }) << p;
  }
}

// One frame of a real file, checked against its text: the header (line 1),
// the frame count, and some values of frame `index` as the line `line` has them.
struct RealFile {
  const char* path;
  const char* version;
  const char* name;
  double rate;
  std::size_t frames;
  std::size_t index;
  long number;
  int line;
  std::vector<std::pair<int, double>> values;  // FAP, value
};

void PrintTo(const RealFile& r, std::ostream* os) {
  *os << r.path << ", frame " << r.index;
}

class RealFapFile : public ::testing::TestWithParam<RealFile> {};

TEST_P(RealFapFile, HoldsWhatItsTextSays) {
  const RealFile& r = GetParam();
  const FapSequence s = load_fap_file(file(r.path));
  EXPECT_EQ(s.header.version, r.version);
  EXPECT_EQ(s.header.name, r.name);
  EXPECT_DOUBLE_EQ(s.header.frame_rate, r.rate);
  ASSERT_EQ(s.frames.size(), r.frames);
  const FapFrame& f = s.frames[r.index];
  EXPECT_EQ(f.number, r.number);
  EXPECT_EQ(f.line, r.line);
  for (const auto& [fap, v] : r.values) {
    EXPECT_TRUE(f.mask[static_cast<std::size_t>(fap - 1)]) << "FAP " << fap << " not sent";
    EXPECT_DOUBLE_EQ(f.values[static_cast<std::size_t>(fap - 1)], v) << "FAP " << fap;
  }
}

const char* const kGreta = "C:\\greta output\\Welcome 2.fap";
const char* const kXface = "C:\\Users\\balci\\Work\\FACE\\exml2fap\\files\\TempFile";

INSTANTIATE_TEST_SUITE_P(
    Producers, RealFapFile,
    ::testing::Values(
        // Greta's layout (FAPFileWriter): the path as the name, spaces and
        // all; 69-entry masks; line 3 "0 0 120 300 300 " is FAP 1's one
        // value (not played), then FAPs 3, 19 and 20.
        RealFile{
            "greta_layout.fap", "2.1", kGreta, 25, 3, 0, 0, 3, {{3, 120}, {19, 300}, {20, 300}}},
        RealFile{"greta_layout.fap", "2.1", kGreta, 25, 3, 1, 1, 5, {{3, 80}}},
        // VREng's layout (its jag.fap): version 2.0, tabs, CR LF, frames from 1;
        // line 3 "1<tab>-50<tab>-7000" sets FAPs 3 and 48
        RealFile{
            "vreng_layout.fap", "2.0", "vreng_layout", 10, 2, 0, 1, 3, {{3, -50}, {48, -7000}}},
        RealFile{"vreng_layout.fap", "2.0", "vreng_layout", 10, 2, 1, 2, 5, {{3, 35}}},
        // Xface's samples from its exml2fap: a Windows path as the name, CR LF;
        // line 111 "54 70 -84 -14 ..." and line 109 "53 110 17 -44 ..."
        RealFile{"real/xface/anger.fap",
                 "2.1",
                 kXface,
                 25,
                 108,
                 54,
                 54,
                 111,
                 {{3, 70}, {4, -84}, {5, -14}}},
        RealFile{
            "real/xface/pride.fap", "2.1", kXface, 25, 107, 53, 53, 109, {{3, 110}, {5, -44}}}),
    [](const ::testing::TestParamInfo<RealFile>& p) {
      std::string n = std::string(p.param.path) + "_" + std::to_string(p.param.index);
      for (char& c : n) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return n;
    });

// Greta's lip model sends FAP 1 as one number of its own: read, not played.
TEST(FapRealFiles, GretaOneValueVisemeIsNotPlayed) {
  const FapSequence s = load_fap_file(file("greta_layout.fap"));
  EXPECT_FALSE(s.frames[0].mask[0]);
  EXPECT_TRUE(s.frames[0].unplayed[0]);
  EXPECT_FALSE(s.used[0]);
  EXPECT_TRUE(s.unplayed[0]);
  EXPECT_TRUE(s.frames[2].mask.none());  // line 7 "2 ": nothing sent
}

}  // namespace
}  // namespace facectl
