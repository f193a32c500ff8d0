#include "firmware-host/inputs/phone_visemes.hpp"

#include <array>
#include <string>
#include <utility>

namespace facectl {
namespace {

using Entry = std::pair<std::string_view, int>;

constexpr std::array kSilence{std::string_view("sil"),   std::string_view("sp"),
                              std::string_view("spn"),   std::string_view("<eps>"),
                              std::string_view("<sil>"), std::string_view("pau"),
                              std::string_view("#")};

constexpr std::array<Entry, 52> kArpabet{{
    {"P", 1},   {"B", 1},    {"M", 1},    {"EM", 1},  {"F", 2},   {"V", 2},   {"TH", 3},
    {"DH", 3},  {"T", 4},    {"D", 4},    {"DX", 4},  {"Q", 4},   {"K", 5},   {"G", 5},
    {"NG", 5},  {"HH", 5},   {"CH", 6},   {"JH", 6},  {"SH", 6},  {"ZH", 6},  {"S", 7},
    {"Z", 7},   {"N", 8},    {"L", 8},    {"NX", 8},  {"EL", 8},  {"EN", 8},  {"R", 9},
    {"ER", 9},  {"AXR", 9},  {"AA", 10},  {"AE", 10}, {"AH", 10}, {"AW", 10}, {"AY", 10},
    {"EH", 11}, {"EY", 11},  {"AX", 11},  {"IH", 12}, {"IY", 12}, {"IX", 12}, {"Y", 12},
    {"AO", 13}, {"OW", 13},  {"OY", 13},  {"UH", 14}, {"UW", 14}, {"UX", 14}, {"W", 14},
    {"WH", 14}, {"AH0", 11}, {"AX0", 11},
}};

constexpr std::array<Entry, 78> kIpa{{
    {"p", 1},   {"b", 1},  {"m", 1},   {"kp", 1},  {"ɡb", 1},  {"f", 2},   {"v", 2},   {"ɱ", 2},
    {"θ", 3},   {"ð", 3},  {"t", 4},   {"d", 4},   {"ɾ", 4},   {"ʔ", 4},   {"k", 5},   {"ɡ", 5},
    {"g", 5},   {"ŋ", 5},  {"c", 5},   {"ɟ", 5},   {"x", 5},   {"ɣ", 5},   {"q", 5},   {"h", 5},
    {"ɦ", 5},   {"tʃ", 6}, {"dʒ", 6},  {"ʧ", 6},   {"ʤ", 6},   {"ʃ", 6},   {"ʒ", 6},   {"ç", 6},
    {"s", 7},   {"z", 7},  {"n", 8},   {"l", 8},   {"ɫ", 8},   {"ɲ", 8},   {"ʎ", 8},   {"ɬ", 8},
    {"ɹ", 9},   {"r", 9},  {"ɻ", 9},   {"ɚ", 9},   {"ɝ", 9},   {"ɑ", 10},  {"a", 10},  {"ɐ", 10},
    {"ʌ", 10},  {"æ", 10}, {"aj", 10}, {"aɪ", 10}, {"aw", 10}, {"aʊ", 10}, {"ə", 11},  {"ɛ", 11},
    {"e", 11},  {"ɜ", 11}, {"ej", 11}, {"eɪ", 11}, {"ɪ", 12},  {"i", 12},  {"ɨ", 12},  {"j", 12},
    {"ɔ", 13},  {"o", 13}, {"ɒ", 13},  {"ow", 13}, {"oʊ", 13}, {"əʊ", 13}, {"ɔj", 13}, {"ɔɪ", 13},
    {"oj", 13}, {"ʊ", 14}, {"u", 14},  {"ʉ", 14},  {"w", 14},  {"ɥ", 14},
}};

constexpr std::array<Entry, 12> kSampa{{
    {"{", 10},
    {"A", 10},
    {"@", 11},
    {"E", 11},
    {"I", 12},
    {"O", 13},
    {"U", 14},
    {"3", 9},
    {"3r", 9},
    {"tS", 6},
    {"dZ", 6},
    {"r\\", 9},
}};

template <std::size_t N>
int find(const std::array<Entry, N>& table, std::string_view key) {
  for (const auto& [k, v] : table) {
    if (k == key) return v;
  }
  return -1;
}

std::string upper_ascii(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return out;
}

// Drops marks that change a phone's sound but not its lip shape: spacing
// modifier letters (ʰ ʲ ʷ ː ˈ ˞ ...), combining diacritics and tie bars,
// superscript n, and ASCII ':' used for length. Bytes that are not valid
// UTF-8 are kept, so such a label is simply not found.
std::string strip_marks(std::string_view s) {
  std::string out;
  std::size_t i = 0;
  while (i < s.size()) {
    const auto b = static_cast<unsigned char>(s[i]);
    std::size_t len = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : 4;
    if (i + len > s.size()) len = 1;
    char32_t cp = b;
    if (len == 2) cp = ((b & 0x1Fu) << 6) | (static_cast<unsigned char>(s[i + 1]) & 0x3Fu);
    if (len == 3) {
      cp = ((b & 0x0Fu) << 12) | ((static_cast<unsigned char>(s[i + 1]) & 0x3Fu) << 6) |
           (static_cast<unsigned char>(s[i + 2]) & 0x3Fu);
    }
    const bool mark = cp == U':' || (cp >= 0x2B0 && cp <= 0x2FF) || (cp >= 0x300 && cp <= 0x36F) ||
                      (cp >= 0x1DC0 && cp <= 0x1DFF) || cp == 0x207F;
    if (!mark) out.append(s.substr(i, len));
    i += len;
  }
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

int viseme_of_phone(std::string_view label) {
  label = trim(label);
  const std::string upper = upper_ascii(label);
  if (label.empty()) return kVisemeNone;
  for (std::string_view s : kSilence) {
    if (upper == upper_ascii(s)) return kVisemeNone;
  }
  // Looked up with the digit first: unstressed AH0 is a schwa.
  if (const int v = find(kArpabet, upper); v >= 0) return v;
  std::string_view bare = upper;
  if (bare.size() > 1 && bare.back() >= '0' && bare.back() <= '2') bare.remove_suffix(1);
  if (const int v = find(kArpabet, bare); v >= 0) return v;
  const std::string ipa = strip_marks(label);
  if (const int v = find(kIpa, ipa); v >= 0) return v;
  return find(kSampa, ipa);
}

int viseme_of_sampa_phone(std::string_view label) {
  // X-SAMPA capitals that ARPAbet spells otherwise, case kept.
  static constexpr std::array<Entry, 7> kSampaCapitals{{
      {"V", kVisemeA},      // ʌ, not v
      {"S", kVisemeChJSh},  // ʃ, not s
      {"Z", kVisemeChJSh},  // ʒ, not z
      {"T", kVisemeTh},     // θ, not t
      {"D", kVisemeTh},     // ð, not d
      {"N", kVisemeKG},     // ŋ, not n
      {"Q", kVisemeO},      // ɒ, not a glottal stop
  }};
  const std::string_view t = trim(label);
  if (const int v = find(kSampaCapitals, t); v >= 0) return v;
  if (const int v = find(kSampa, t); v >= 0) return v;
  return viseme_of_phone(label);
}

int viseme_of_rhubarb_shape(char shape) {
  switch (shape) {
    case 'A':
      return kVisemePBM;
    case 'B':
      return kVisemeSZ;
    case 'C':
      return kVisemeE;
    case 'D':
      return kVisemeA;
    case 'E':
      return kVisemeO;
    case 'F':
      return kVisemeU;
    case 'G':
      return kVisemeFV;
    case 'H':
      return kVisemeNL;
    case 'X':
      return kVisemeNone;
    default:
      return -1;
  }
}

}  // namespace facectl
