#include "firmware-host/fap/fap_file.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "facectl/face/bounded_file.hpp"
#include "facectl/face/input_error.hpp"
#include "firmware-host/inputs/input_limits.hpp"

namespace facectl {
namespace {

struct Token {
  std::string_view text;
  int column = 0;  // 1-based
};

std::vector<Token> split(std::string_view line) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i >= line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

std::string_view strip_cr(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

bool skipped(std::string_view line) {
  const auto first = line.find_first_not_of(" \t");
  return first == std::string_view::npos || line[first] == '#';
}

std::optional<long> to_long(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  long v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

// Any decimal number; inf and nan parse (so that they can be named as non-finite).
std::optional<double> to_double(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

// The shortest text that reads back as v: 25, 2160000, 1e-300.
std::string shortest(double v) {
  char buf[32];
  return {buf, std::to_chars(buf, buf + sizeof buf, v).ptr};
}

std::string quoted(std::string_view s) {
  std::string out(1, '\'');
  out.append(s);
  out.push_back('\'');
  return out;
}

std::string fap_label(int number) {
  return "FAP " + std::to_string(number) + " " + std::string(fap_info(number).name);
}

// Greta writes its frames' 70 slots from index 1: FAP 1..68, then slot 69,
// which no FAP uses and which it writes as 0 (docs/FAP.md, leniencies).
constexpr std::size_t kGretaMaskEntries = kFapCount + 1;

// The number of values FAP n takes on a values line. Greta writes one value
// for every FAP, FAP 1 and 2 included.
int fields_of(int number, bool greta) {
  if (greta) return 1;
  if (number == 1) return 4;
  if (number == 2) return 6;
  return 1;
}

// A line that starts a new sequence in a stream: a mask starts with 0 or 1,
// a header with its version; the name may add fields (Greta).
bool looks_like_header(const std::vector<Token>& t) {
  return t.size() >= 4 && t[0].text != "0" && t[0].text != "1";
}

}  // namespace

void FapReader::fail(int line, int column, std::string_view expected,
                     std::string_view found) const {
  std::string message = source_ + ":" + std::to_string(line);
  if (column > 0) message += ":" + std::to_string(column);
  message += ": expected " + std::string(expected) + ", found " + std::string(found);
  throw FapFormatError(message, line);
}

std::optional<FapFrame> FapReader::feed(std::string_view raw, int line_number) {
  const std::string_view line = strip_cr(raw);
  if (skipped(line)) return std::nullopt;
  switch (state_) {
    case State::kHeader:
      read_header(line, line_number);
      state_ = State::kMask;
      return std::nullopt;
    case State::kMask:
      // A stream may restart with a new header; a file has exactly one.
      if (allow_new_header_ && looks_like_header(split(line))) {
        read_header(line, line_number);
        last_number_.reset();
        return std::nullopt;
      }
      read_mask(line, line_number);
      state_ = State::kValues;
      return std::nullopt;
    case State::kValues: {
      FapFrame frame = read_values(line, line_number);
      state_ = State::kMask;
      return frame;
    }
  }
  return std::nullopt;
}

void FapReader::read_header(std::string_view line, int n) {
  const auto t = split(line);
  const char* layout = "a header 'version name frame_rate frame_count' (e.g. '2.1 demo 25 100')";
  if (t.size() < 4) {
    fail(n, 1, layout, std::to_string(t.size()) + " field" + (t.size() == 1 ? "" : "s"));
  }
  FapHeader h;
  if (t[0].text != "2.0" && t[0].text != "2.1") {
    fail(n, t[0].column, "FAP file version 2.0 or 2.1 in the header", quoted(t[0].text));
  }
  h.version = std::string(t[0].text);
  // The rate and count are the last two fields; the name is everything
  // between, as written: Greta puts its file path there, spaces and all.
  const Token& rate_field = t[t.size() - 2];
  const Token& count_field = t.back();
  const Token& last_word = t[t.size() - 3];
  const auto name_start = static_cast<std::size_t>(t[1].column - 1);
  const auto name_end = static_cast<std::size_t>(last_word.column - 1) + last_word.text.size();
  h.name = std::string(line.substr(name_start, name_end - name_start));
  const auto rate = to_double(rate_field.text);
  if (!rate || !std::isfinite(*rate) || *rate <= 0.0) {
    fail(n, rate_field.column, "a frame rate > 0 (frames per second)", quoted(rate_field.text));
  }
  h.frame_rate = *rate;
  const auto count = to_long(count_field.text);
  if (!count || *count < 0) {
    fail(n, count_field.column, "a frame count (an integer >= 0)", quoted(count_field.text));
  }
  h.frame_count = *count;
  header_ = h;
}

void FapReader::read_mask(std::string_view line, int n) {
  const auto t = split(line);
  if (t.size() != kFapCount && t.size() != kGretaMaskEntries) {
    fail(n, 1, "a mask line of 68 entries (0 or 1, one per FAP), or Greta's 69",
         std::to_string(t.size()) + " entries");
  }
  const bool greta = t.size() == kGretaMaskEntries;
  // Greta's slot 69 is no FAP: only its 0 has a meaning.
  if (greta && t.back().text != "0") {
    fail(n, t.back().column, "0 as mask entry 69 (Greta's unused slot after FAP 68)",
         quoted(t.back().text));
  }
  FapMask mask;
  for (std::size_t i = 0; i < kFapCount; ++i) {
    if (t[i].text == "1") {
      mask.set(i);
    } else if (t[i].text != "0") {
      fail(n, t[i].column,
           "0 or 1 as mask entry " + std::to_string(i + 1) + " (" +
               fap_label(static_cast<int>(i) + 1) + ")",
           quoted(t[i].text));
    }
  }
  mask_ = mask;
  greta_mask_ = greta;
  mask_line_ = n;
}

FapFrame FapReader::read_values(std::string_view line, int n) {
  const auto t = split(line);
  std::size_t expected = 1;
  for (int f = 1; f <= kFapCount; ++f) {
    if (mask_[static_cast<std::size_t>(f - 1)]) {
      expected += static_cast<std::size_t>(fields_of(f, greta_mask_));
    }
  }
  if (t.size() != expected) {
    fail(n, 1,
         std::to_string(expected) + " fields: the frame number and " +
             std::to_string(expected - 1) + " value" + (expected == 2 ? "" : "s") + " for the " +
             std::to_string(mask_.count()) + " FAPs the mask at line " +
             std::to_string(mask_line_) + " selects" +
             (greta_mask_ ? " (its 69 entries are Greta's: one value each)"
                          : " (FAP 1 takes 4, FAP 2 takes 6)"),
         std::to_string(t.size()) + " fields");
  }
  FapFrame frame;
  frame.mask = mask_;
  frame.line = n;
  const auto number = to_long(t[0].text);
  if (!number || *number < 0) {
    fail(n, t[0].column, "a frame number (an integer >= 0)", quoted(t[0].text));
  }
  if (last_number_ && *number <= *last_number_) {
    fail(n, t[0].column,
         "a frame number greater than the previous frame's " + std::to_string(*last_number_),
         std::to_string(*number));
  }
  frame.number = *number;
  std::size_t k = 1;
  auto integer = [&](int fap, std::string_view field, int lo, int hi) {
    const Token& tok = t[k++];
    const auto v = to_long(tok.text);
    if (!v || *v < lo || *v > hi) {
      fail(n, tok.column,
           std::string(field) + " of " + fap_label(fap) + " as an integer in " +
               std::to_string(lo) + ".." + std::to_string(hi),
           quoted(tok.text));
    }
    return static_cast<int>(*v);
  };
  for (int f = 1; f <= kFapCount; ++f) {
    const auto bit = static_cast<std::size_t>(f - 1);
    if (!mask_[bit]) continue;
    if (greta_mask_ && f <= 2) {
      // Greta's one value has a meaning of its own (its LipBlender divides
      // FAP 1 by 1000 as a blend factor), not the standard's fields: checked,
      // kept out of play.
      (void)integer(f, "Greta's one value", std::numeric_limits<int>::min(),
                    std::numeric_limits<int>::max());
      frame.mask.reset(bit);
      frame.unplayed.set(bit);
    } else if (f == 1) {
      frame.viseme.select1 = integer(1, "viseme_select1", 0, 14);
      frame.viseme.select2 = integer(1, "viseme_select2", 0, 14);
      frame.viseme.blend = integer(1, "viseme_blend", 0, 63);
      frame.viseme.def = integer(1, "viseme_def", 0, 1);
    } else if (f == 2) {
      frame.expression.select1 = integer(2, "expression_select1", 0, 6);
      frame.expression.intensity1 = integer(2, "expression_intensity1", 0, 63);
      frame.expression.select2 = integer(2, "expression_select2", 0, 6);
      frame.expression.intensity2 = integer(2, "expression_intensity2", 0, 63);
      frame.expression.init_face = integer(2, "init_face", 0, 1);
      frame.expression.def = integer(2, "expression_def", 0, 1);
    } else {
      const Token& tok = t[k++];
      const auto v = to_double(tok.text);
      if (!v) fail(n, tok.column, "a number as the value of " + fap_label(f), quoted(tok.text));
      if (!std::isfinite(*v)) {
        fail(n, tok.column, "a finite number as the value of " + fap_label(f), quoted(tok.text));
      }
      frame.values[static_cast<std::size_t>(f - 1)] = *v;
    }
  }
  last_number_ = frame.number;
  ++frames_;
  return frame;
}

FapSequence parse_fap_text(std::string_view text, const std::string& source) {
  FapReader reader(source);
  FapSequence seq;
  seq.source = source;
  int line_number = 0;
  int header_line = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    ++line_number;
    const bool had_header = reader.has_header();
    auto frame = reader.feed(text.substr(pos, end - pos), line_number);
    if (!had_header && reader.has_header()) {
      header_line = line_number;
      seq.header = reader.header();
    }
    if (frame) {
      if (static_cast<long>(seq.frames.size()) == seq.header.frame_count) {
        reader.fail(line_number, 0,
                    "no more frames: the header at line " + std::to_string(header_line) +
                        " declares " + std::to_string(seq.header.frame_count),
                    "frame " + std::to_string(frame->number) + " beyond them");
      }
      // A file's length bounds what `simulate` computes and writes; a stream
      // (FapReader alone) may run for days.
      if (seq.time_of(*frame) > kMaxShowSeconds) {
        reader.fail(line_number, 1,
                    "a frame at most " + shortest(kMaxShowSeconds) + " s in (frame " +
                        shortest(std::floor(kMaxShowSeconds * seq.header.frame_rate)) + " at " +
                        shortest(seq.header.frame_rate) + " fps)",
                    "frame " + std::to_string(frame->number));
      }
      seq.used |= frame->mask;
      seq.unplayed |= frame->unplayed;
      seq.frames.push_back(*frame);
    }
    pos = end + 1;
  }
  const int eof_line = line_number + 1;
  if (!reader.has_header()) {
    reader.fail(eof_line, 0, "a header 'version name frame_rate frame_count'",
                "the end of the input");
  }
  if (reader.mid_frame()) {
    reader.fail(
        eof_line, 0,
        "the values line of the frame whose mask is at line " + std::to_string(reader.mask_line()),
        "the end of the input (truncated)");
  }
  if (static_cast<long>(seq.frames.size()) < seq.header.frame_count) {
    reader.fail(eof_line, 0,
                std::to_string(seq.header.frame_count) + " frames as the header at line " +
                    std::to_string(header_line) + " declares",
                "the end of the input after " + std::to_string(seq.frames.size()) + " (truncated)");
  }
  if (seq.frames.empty()) {
    reader.fail(header_line, 0, "a frame count of at least 1 in the header", "0 frames");
  }
  return seq;
}

std::string format_fap_text(const FapSequence& seq) {
  std::ostringstream out;
  out.precision(17);
  out << seq.header.version << ' ' << seq.header.name << ' ' << seq.header.frame_rate << ' '
      << seq.frames.size() << '\n';
  for (const FapFrame& f : seq.frames) {
    for (std::size_t i = 0; i < kFapCount; ++i) out << (i ? " " : "") << (f.mask[i] ? 1 : 0);
    out << '\n' << f.number;
    if (f.mask[0]) {
      out << ' ' << f.viseme.select1 << ' ' << f.viseme.select2 << ' ' << f.viseme.blend << ' '
          << f.viseme.def;
    }
    if (f.mask[1]) {
      const ExpressionParams& e = f.expression;
      out << ' ' << e.select1 << ' ' << e.intensity1 << ' ' << e.select2 << ' ' << e.intensity2
          << ' ' << e.init_face << ' ' << e.def;
    }
    for (std::size_t i = 2; i < kFapCount; ++i) {
      if (f.mask[i]) out << ' ' << f.values[i];
    }
    out << '\n';
  }
  return out.str();
}

FapSequence load_fap_file(const std::string& path) {
  std::string text;
  try {
    text = face::read_bounded_file(path, kMaxFapFileBytes, "FAP file");
  } catch (const face::InputError& e) {
    throw ConfigError(e.what());
  }
  return parse_fap_text(text, path);
}

}  // namespace facectl
