#include "firmware-host/inputs/input_format.hpp"

#include <array>
#include <utility>

#include "firmware-host/inputs/live_link_face_csv.hpp"
#include "firmware-host/inputs/openface_csv.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

constexpr std::array<std::pair<InputFormat, const char*>, 10> kNames = {{
    {InputFormat::kShow, "show"},
    {InputFormat::kFap, "fap"},
    {InputFormat::kLiveLinkFaceCsv, "live_link_face"},
    {InputFormat::kMediapipeJson, "mediapipe"},
    {InputFormat::kOpenFaceCsv, "openface"},
    {InputFormat::kRhubarbJson, "rhubarb_json"},
    {InputFormat::kRhubarbTsv, "rhubarb_tsv"},
    {InputFormat::kTextGrid, "textgrid"},
    {InputFormat::kAudio, "audio"},
    {InputFormat::kAudioPhonemes, "audio_phonemes"},
}};

// The text without a UTF-8 BOM and leading blanks.
std::string_view skip_blanks(std::string_view t) {
  if (t.substr(0, 3) == "\xEF\xBB\xBF") t.remove_prefix(3);
  while (!t.empty() &&
         (t.front() == ' ' || t.front() == '\t' || t.front() == '\r' || t.front() == '\n')) {
    t.remove_prefix(1);
  }
  return t;
}

bool starts_with(std::string_view t, std::string_view p) {
  return t.substr(0, p.size()) == p;
}

}  // namespace

std::optional<InputFormat> parse_input_format(std::string_view name) {
  for (const auto& [f, n] : kNames) {
    if (name == n) return f;
  }
  return std::nullopt;
}

const char* input_format_name(InputFormat format) {
  for (const auto& [f, n] : kNames) {
    if (f == format) return n;
  }
  return "?";
}

std::string input_format_names() {
  std::string s;
  for (const auto& [f, n] : kNames) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

std::optional<InputFormat> detect_input_format(std::string_view text) {
  if ((starts_with(text, "RIFF") && text.size() >= 12 && text.substr(8, 4) == "WAVE") ||
      starts_with(text, "fLaC") || starts_with(text, "OggS")) {
    return InputFormat::kAudio;
  }
  // UTF-16 (with its BOM) is how Praat saves a TextGrid with non-ASCII labels.
  if (starts_with(text, "\xFF\xFE") || starts_with(text, "\xFE\xFF")) return InputFormat::kTextGrid;
  const std::string_view t = skip_blanks(text);
  const std::string_view head = t.substr(0, kDetectBytes);
  if (starts_with(t, "File type = \"ooTextFile")) return InputFormat::kTextGrid;
  // UTF-16 without a BOM: "ooText" with a NUL between the letters (either order).
  if (head.find(std::string_view("o\0o\0T\0e\0x\0t", 11)) != std::string_view::npos) {
    return InputFormat::kTextGrid;
  }
  if (looks_like_live_link_face_csv(t)) return InputFormat::kLiveLinkFaceCsv;
  if (looks_like_openface_csv(t)) return InputFormat::kOpenFaceCsv;
  if (starts_with(t, "show:") || head.find("\nshow:") != std::string_view::npos) {
    return InputFormat::kShow;
  }
  if (starts_with(t, "{") || starts_with(t, "[")) {
    const bool cue = head.find("\"start\"") != std::string_view::npos &&
                     head.find("\"value\"") != std::string_view::npos;
    if (head.find("\"mouthCues\"") != std::string_view::npos || (starts_with(t, "[") && cue)) {
      return InputFormat::kRhubarbJson;  // Rhubarb's file, or its cue list alone
    }
    if (head.find("\"score\"") != std::string_view::npos ||
        head.find("lendshapes\"") != std::string_view::npos) {
      return InputFormat::kMediapipeJson;
    }
    return std::nullopt;
  }
  // FAP: a version 2.0/2.1 header line, after comments.
  std::string_view r = t;
  while (starts_with(r, "#")) {
    const std::size_t nl = r.find('\n');
    if (nl == std::string_view::npos) return std::nullopt;
    r = skip_blanks(r.substr(nl + 1));
  }
  if (starts_with(r, "2.1 ") || starts_with(r, "2.0 ") || starts_with(r, "2.1\t") ||
      starts_with(r, "2.0\t")) {
    return InputFormat::kFap;
  }
  // Rhubarb TSV: "0.00<TAB>X" lines.
  const std::size_t tab = t.find('\t');
  double start = 0;
  if (tab != std::string_view::npos && tab < 16 && t.find('\n') > tab &&
      parse_number(t.substr(0, tab), start)) {
    const char shape = tab + 1 < t.size() ? t[tab + 1] : 0;
    if ((shape >= 'A' && shape <= 'H') || shape == 'X') return InputFormat::kRhubarbTsv;
  }
  return std::nullopt;
}

}  // namespace facectl
