// Praat TextGrid, long and short text formats (parse_textgrid). Both are read
// the way Praat reads them: as a stream of numbers, quoted strings and <flags>,
// skipping the key words and [indices] of the long format.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>

#include "firmware-host/inputs/phoneme_track.hpp"
#include "firmware-host/inputs/phoneme_track_builder.hpp"

namespace facectl {
namespace {

void append_utf8(std::string& out, char32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// UTF-16 (after its BOM) as UTF-8. Praat writes UTF-16 with a BOM whenever a
// label is not ASCII.
std::string utf16_to_utf8(std::string_view bytes, bool big_endian, const PhonemeTrackBuilder& b) {
  std::string out;
  out.reserve(bytes.size());
  int line = 1;
  const auto unit = [&](std::size_t i) -> char32_t {
    const auto hi = static_cast<unsigned char>(bytes[i + (big_endian ? 0 : 1)]);
    const auto lo = static_cast<unsigned char>(bytes[i + (big_endian ? 1 : 0)]);
    return static_cast<char32_t>(hi << 8 | lo);
  };
  if (bytes.size() % 2 != 0) {
    b.fail(1, {}, "UTF-16 text of whole 2-byte units", "an odd number of bytes");
  }
  for (std::size_t i = 0; i < bytes.size(); i += 2) {
    char32_t cp = unit(i);
    if (cp >= 0xD800 && cp <= 0xDBFF && i + 2 < bytes.size()) {
      const char32_t low = unit(i + 2);
      if (low >= 0xDC00 && low <= 0xDFFF) {
        cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
        i += 2;
      }
    }
    if (cp >= 0xD800 && cp <= 0xDFFF) b.fail(line, {}, "UTF-16 text", "an unpaired surrogate");
    if (cp == U'\n') ++line;
    append_utf8(out, cp);
  }
  return out;
}

struct Token {
  enum Kind { kNumber, kString, kFlag, kWord, kEnd } kind = kEnd;
  std::string text;
  int line = 0;
};

std::string describe(const Token& t) {
  switch (t.kind) {
    case Token::kNumber:
      return "the number " + t.text.substr(0, 40);
    case Token::kString:
      return "the string \"" + t.text.substr(0, 40) + (t.text.size() > 40 ? "...\"" : "\"");
    case Token::kFlag:
      return quote_found(t.text);
    case Token::kWord:
      return quote_found(t.text);
    case Token::kEnd:
      break;
  }
  return "the end of the file";
}

// The long format's keys, skipped like Praat skips them.
bool is_key(std::string_view w) {
  static constexpr std::string_view kKeys[] = {
      "File", "type",      "Object", "class", "xmin", "xmax",   "tiers", "size",
      "item", "intervals", "points", "name",  "text", "number", "mark",  "time"};
  return std::find(std::begin(kKeys), std::end(kKeys), w) != std::end(kKeys);
}

class Lexer {
 public:
  Lexer(std::string_view text, const PhonemeTrackBuilder& b) : text_(text), b_(b) {}

  Token next() {
    skip();
    Token t;
    t.line = line_;
    if (pos_ >= text_.size()) return t;
    const char c = text_[pos_];
    if (c == '"') {
      t.kind = Token::kString;
      for (++pos_;; ++pos_) {
        if (pos_ >= text_.size()) {
          b_.fail(t.line, {}, "a closing '\"' for the string opened here", "the end of the file");
        }
        if (text_[pos_] == '"') {
          if (pos_ + 1 < text_.size() && text_[pos_ + 1] == '"') {
            t.text += '"';
            ++pos_;
            continue;
          }
          ++pos_;
          break;
        }
        if (text_[pos_] == '\n') ++line_;
        t.text += text_[pos_];
      }
      return t;
    }
    const std::size_t begin = pos_;
    if (c == '<') {
      pos_ = std::min(text_.find('>', pos_), text_.size() - 1) + 1;
      t.kind = Token::kFlag;
    } else {
      while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])) &&
             text_[pos_] != '"') {
        ++pos_;
      }
      const bool numeric =
          std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
      t.kind = numeric ? Token::kNumber : Token::kWord;
    }
    t.text = text_.substr(begin, pos_ - begin);
    return t;
  }

 private:
  // Skips white space, "! comments", "[index]", "=", ":" and key words.
  void skip() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c)) || c == '=' || c == ':') {
        ++pos_;
      } else if (c == '!') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (c == '[') {
        // Only up to the line's end: a search of the whole rest per '[' is
        // quadratic on a file of one long line.
        const std::size_t close = text_.find_first_of("]\n", pos_);
        if (close == std::string_view::npos || text_[close] != ']') return;
        pos_ = close + 1;
      } else if (std::isalpha(static_cast<unsigned char>(c))) {
        std::size_t end = pos_;
        while (end < text_.size() && std::isalpha(static_cast<unsigned char>(text_[end]))) ++end;
        if (!is_key(text_.substr(pos_, end - pos_))) return;
        pos_ = end;
        if (pos_ < text_.size() && text_[pos_] == '?') ++pos_;
      } else {
        return;
      }
    }
  }

  std::string_view text_;
  const PhonemeTrackBuilder& b_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

struct Interval {
  double xmin, xmax;
  std::string text;
  int line_min, line_text;
};

struct Tier {
  std::string name;
  int line = 0;
  std::vector<Interval> intervals;
};

class Reader {
 public:
  Reader(std::string_view text, const PhonemeTrackBuilder& b)
      : lex_(text, b), b_(b), size_(text.size()) {
    tok_ = lex_.next();
  }
  const Token& peek() const { return tok_; }
  Token take() {
    Token t = std::move(tok_);
    tok_ = lex_.next();
    return t;
  }
  std::string string(std::string_view what) {
    if (tok_.kind != Token::kString) b_.fail(tok_.line, {}, what, describe(tok_));
    return take().text;
  }
  double number(std::string_view what) {
    double v = 0.0;
    const std::string& s = tok_.text;
    const char* first = s.data() + (s.starts_with('+') ? 1 : 0);
    const auto [p, ec] = std::from_chars(first, s.data() + s.size(), v);
    if (tok_.kind != Token::kNumber || ec != std::errc() || p != s.data() + s.size()) {
      b_.fail(tok_.line, {}, what, describe(tok_));
    }
    take();
    return v;
  }
  double time(std::string_view what) {
    const int line = tok_.line;
    const std::string text = tok_.text;
    const double t = number(what);
    b_.check_time(t, line, {}, "the number " + text);
    return t;
  }
  long count(std::string_view what) {
    const int line = tok_.line;
    const std::string text = tok_.text;
    const double v = number(what);
    // Each item takes at least two more bytes, so a larger count cannot be right.
    if (v < 0 || v != std::floor(v) || v > static_cast<double>(size_)) {
      b_.fail(line, {}, what, "the number " + text);
    }
    return static_cast<long>(v);
  }

 private:
  Lexer lex_;
  const PhonemeTrackBuilder& b_;
  std::size_t size_;
  Token tok_;
};

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool is_phone_tier(std::string_view name) {
  const std::string n = lower(name);
  return n == "phones" || n == "phone" || n == "phonemes" || n == "segments" || n == "phonalign" ||
         n.ends_with(" - phones");
}

std::string tier_list(const std::vector<Tier>& tiers) {
  std::string out;
  for (const Tier& t : tiers) out += (out.empty() ? "\"" : ", \"") + t.name + "\"";
  return out.empty() ? "no interval tier" : "interval tiers " + out;
}

const Tier& choose_tier(const std::vector<Tier>& tiers, std::string_view wanted, int line,
                        const PhonemeTrackBuilder& b) {
  std::vector<const Tier*> hits;
  for (const Tier& t : tiers) {
    if (wanted.empty() ? is_phone_tier(t.name) : lower(t.name) == lower(wanted)) hits.push_back(&t);
  }
  if (hits.empty() && wanted.empty() && tiers.size() == 1) hits.push_back(&tiers[0]);
  if (hits.size() == 1) return *hits[0];
  std::string expected = wanted.empty()
                             ? "one interval tier named phones (or phone, phonemes, segments)"
                             : "an interval tier named \"" + std::string(wanted) + "\"";
  if (hits.size() > 1) expected += " (several match: name one)";
  b.fail(line, {}, expected, tier_list(tiers));
}

}  // namespace

PhonemeTrack parse_textgrid(std::string_view text, const std::string& file,
                            std::string_view tier_name) {
  PhonemeTrackBuilder b(file);
  std::string decoded;
  if (text.starts_with("\xEF\xBB\xBF")) {
    text.remove_prefix(3);
  } else if (text.starts_with("\xFF\xFE") || text.starts_with("\xFE\xFF")) {
    decoded = utf16_to_utf8(text.substr(2), text[0] == '\xFE', b);
    text = decoded;
  } else if (text.size() >= 2 && (text[0] == '\0') != (text[1] == '\0')) {
    decoded = utf16_to_utf8(text, text[0] == '\0', b);  // UTF-16 without a BOM
    text = decoded;
  }
  Reader r(text, b);
  const std::string type = r.string("File type = \"ooTextFile\"");
  if (type != "ooTextFile" && type != "ooTextFile short") {
    b.fail(1, {}, "File type = \"ooTextFile\" (a Praat text file)", "\"" + type + "\"");
  }
  const int class_line = r.peek().line;
  if (r.string("Object class = \"TextGrid\"") != "TextGrid") {
    b.fail(class_line, {}, "Object class = \"TextGrid\"", "another class");
  }
  r.time("the TextGrid's xmin");
  const double xmax = r.time("the TextGrid's xmax");
  std::vector<Tier> tiers;
  const int tiers_line = r.peek().line;
  bool exists = true;
  if (r.peek().kind == Token::kFlag) {
    const Token flag = r.take();
    if (flag.text != "<exists>" && flag.text != "<absent>") {
      b.fail(flag.line, {}, "<exists> or <absent>", describe(flag));
    }
    exists = flag.text == "<exists>";
  }
  const long n_tiers = exists ? r.count("the number of tiers") : 0;
  for (long i = 0; i < n_tiers; ++i) {
    const int class_at = r.peek().line;
    const std::string tier_class = r.string("a tier class \"IntervalTier\" or \"TextTier\"");
    if (tier_class != "IntervalTier" && tier_class != "TextTier") {
      b.fail(class_at, {}, "a tier class \"IntervalTier\" or \"TextTier\"",
             "\"" + tier_class + "\"");
    }
    Tier tier;
    tier.line = r.peek().line;
    tier.name = r.string("a tier name");
    r.time("the tier's xmin");
    r.time("the tier's xmax");
    const bool intervals = tier_class == "IntervalTier";
    const long n = r.count(intervals ? "the number of intervals" : "the number of points");
    for (long k = 0; k < n; ++k) {
      if (!intervals) {  // a point tier: time and mark, skipped
        r.number("a point's time");
        r.string("a point's mark");
        continue;
      }
      Interval iv;
      iv.line_min = r.peek().line;
      iv.xmin = r.time("an interval's xmin");
      iv.xmax = r.time("an interval's xmax");
      iv.line_text = r.peek().line;
      iv.text = r.string("an interval's text in double quotes");
      tier.intervals.push_back(std::move(iv));
    }
    if (intervals) tiers.push_back(std::move(tier));
  }
  if (r.peek().kind != Token::kEnd) {
    b.fail(r.peek().line, {}, "the end of the TextGrid after its last tier", describe(r.peek()));
  }
  const Tier& tier = choose_tier(tiers, tier_name, tiers_line, b);
  // SPPAS writes X-SAMPA, where capitals mean other phones than in ARPAbet.
  std::string lower_name = tier.name;
  for (char& c : lower_name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool sampa = lower_name == "phonalign";
  for (const Interval& iv : tier.intervals) {
    // A bad interval is named by its xmin line, a good segment by its label's.
    const bool bad = iv.xmax < iv.xmin || iv.xmin < b.last_end() - kSegmentOverlapTolerance;
    b.add(iv.xmin, iv.xmax, iv.text,
          sampa ? viseme_of_sampa_phone(iv.text) : viseme_of_phone(iv.text),
          bad ? iv.line_min : iv.line_text, "tier \"" + tier.name + "\"");
  }
  return b.finish(xmax);
}

}  // namespace facectl
