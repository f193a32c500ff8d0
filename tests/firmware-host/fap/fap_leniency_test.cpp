// One test per leniency of docs/FAP.md ("What other players write"), and the
// strictness kept beside each.
#include <gtest/gtest.h>

#include <string>

#include "default_fap_head.hpp"
#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_show.hpp"

namespace facectl {
namespace {

// A mask line of `entries` entries with the given FAPs set.
std::string mask(std::initializer_list<int> faps, int entries = kFapCount) {
  std::string s;
  for (int i = 1; i <= entries; ++i) {
    bool on = false;
    for (int f : faps) on = on || f == i;
    s += (i > 1 ? " " : "");
    s += on ? "1" : "0";
  }
  return s + "\n";
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_fap_text(text, "t.fap");
  } catch (const FapFormatError& e) {
    return e.what();
  }
  return "parsed";
}

TEST(FapLeniency, HeaderNameWithSpaces) {
  const FapSequence s =
      parse_fap_text("2.1 AU Interpolation_1192.fap 25 1\n" + mask({3}) + "0 100\n", "t.fap");
  EXPECT_EQ(s.header.name, "AU Interpolation_1192.fap");
  EXPECT_DOUBLE_EQ(s.header.frame_rate, 25.0);
  EXPECT_EQ(s.header.frame_count, 1);
}

TEST(FapLeniency, HeaderNameKeepsItsSpacingThroughTheWriter) {
  const FapSequence a =
      parse_fap_text("2.1 take  2\tof 3 12.5 1\n" + mask({3}) + "0 100\n", "t.fap");
  EXPECT_EQ(a.header.name, "take  2\tof 3");  // the rate and count are the last two
  EXPECT_DOUBLE_EQ(a.header.frame_rate, 12.5);
  const FapSequence b = parse_fap_text(format_fap_text(a), "written");
  EXPECT_EQ(b.header.name, a.header.name);
}

TEST(FapLeniency, HeaderStillNeedsANameRateAndCount) {
  EXPECT_NE(error_of("2.1 25 1\n" + mask({3}) + "0 100\n").find("found 3 fields"),
            std::string::npos);
  EXPECT_NE(error_of("2.1 my clip 25 x\n").find("a frame count"), std::string::npos);
}

TEST(FapLeniency, GretaMaskOf69Entries) {
  const FapSequence s = parse_fap_text(
      "2.1 g 25 2\n" + mask({19, 22}, 69) + "0 626 133 \n" + mask({3}, 69) + "1 50\n", "t.fap");
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[0].mask.count(), 2u);
  EXPECT_DOUBLE_EQ(s.frames[0].values[18], 626.0);
  EXPECT_DOUBLE_EQ(s.frames[0].values[21], 133.0);
  EXPECT_DOUBLE_EQ(s.frames[1].values[2], 50.0);
}

TEST(FapLeniency, GretaSlot69MustBeZero) {
  const std::string e = error_of("2.1 g 25 1\n" + mask({3, 69}, 69) + "0 50 1\n");
  EXPECT_EQ(e.rfind("t.fap:2:137: expected 0 as mask entry 69", 0), 0u) << e;
  EXPECT_NE(e.find("found '1'"), std::string::npos) << e;
}

TEST(FapLeniency, OtherMaskLengthsAreStillRefused) {
  EXPECT_NE(error_of("2.1 g 25 1\n" + mask({3}, 70) + "0 50\n").find("found 70 entries"),
            std::string::npos);
}

TEST(FapLeniency, GretaOneValueFap1And2AreReadNotPlayed) {
  const FapSequence s =
      parse_fap_text("2.1 g 25 1\n" + mask({1, 2, 3}, 69) + "0 500 0 200\n", "t.fap");
  const FapFrame& f = s.frames[0];
  EXPECT_FALSE(f.mask[0]);
  EXPECT_FALSE(f.mask[1]);
  EXPECT_TRUE(f.mask[2]);
  EXPECT_DOUBLE_EQ(f.values[2], 200.0);  // the values after them stay in step
  EXPECT_TRUE(f.unplayed[0] && f.unplayed[1]);
  EXPECT_TRUE(s.unplayed[0] && s.unplayed[1]);
  EXPECT_FALSE(s.used[0]);

  const FapShow show = FapShow::build(s, testing::default_fap_head().mapping);
  EXPECT_EQ(show.unplayed_faps(), (std::vector<int>{1, 2}));
  const auto lines = show.report();
  ASSERT_FALSE(lines.empty());
  EXPECT_NE(lines.back().find("Greta's one-value form"), std::string::npos) << lines.back();
  EXPECT_NE(lines.back().find("1 viseme, 2 expression"), std::string::npos) << lines.back();
}

TEST(FapLeniency, GretaOneValueMustBeAnInteger) {
  const std::string e = error_of("2.1 g 25 1\n" + mask({1, 3}, 69) + "0 0.5 200\n");
  EXPECT_NE(e.find("t.fap:3:3: expected Greta's one value of FAP 1"), std::string::npos) << e;
}

TEST(FapLeniency, A68EntryMaskStillWantsTheStandardsFap1Fields) {
  // Xface's writer and VREng's reader use one value here too, but no file we
  // found needs it, and the count would be the only clue.
  const std::string e = error_of("2.1 g 25 1\n" + mask({1, 3}) + "0 500 200\n");
  EXPECT_NE(e.find("6 fields"), std::string::npos) << e;
  EXPECT_NE(e.find("FAP 1 takes 4"), std::string::npos) << e;
}

TEST(FapLeniency, WhitespaceAsWritten) {
  // tabs (VREng's jag.fap), CR LF (jag.fap, Xface), trailing blanks (Greta,
  // VREng, Xface), blank lines, no newline at the end
  const FapSequence s = parse_fap_text(
      "2.0\tjag\t5\t2\r\n\r\n" + mask({3, 48}) + "0\t57\t-7716 \t\r\n" + mask({3}) + "1 -14",
      "t.fap");
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(s.frames[0].values[47], -7716.0);
  EXPECT_DOUBLE_EQ(s.frames[1].values[2], -14.0);
}

TEST(FapLeniency, AStreamHeaderMayHaveANameWithSpaces) {
  FapReader r("udp");
  r.allow_new_header(true);
  int line = 0;
  auto feed = [&](const std::string& l) { return r.feed(l, ++line); };
  feed("2.1 first 25 0");
  feed(mask({3}).substr(0, 135));
  ASSERT_TRUE(feed("5 100"));
  feed("2.1 AU Interpolation_7.fap 25 0");  // a new sequence: numbering restarts
  EXPECT_EQ(r.header().name, "AU Interpolation_7.fap");
  EXPECT_FALSE(r.last_frame_number());
  feed(mask({3}, 69).substr(0, 137));
  const auto f = feed("0 200");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->number, 0);
}

}  // namespace
}  // namespace facectl
