// Phoneme timings from a lip-sync tool or forced aligner, as MPEG-4 visemes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "firmware-host/inputs/phone_visemes.hpp"

namespace facectl {

struct PhonemeSegment {
  double start_s = 0.0;
  double end_s = 0.0;
  std::string label;  // as written: "EH1", "ɑː", "D" (a Rhubarb shape)
  int viseme = 0;     // MPEG-4 index 0..14; unknown labels are 0 and noted
  int line = 0;       // line of the label in the file
};

// Segments are in time order and do not overlap (they may touch; overlaps of
// up to kSegmentOverlapTolerance, rounding in the writer, are clamped away).
struct PhonemeTrack {
  std::vector<PhonemeSegment> segments;
  std::vector<std::string> notes;  // "file:line: ..." for labels read as silence
  double duration_s = 0.0;         // the file's stated end, else the last segment's end
};

inline constexpr double kSegmentOverlapTolerance = 1e-6;

// All parsers throw ConfigError "file:line: expected ..., found ...".

// Rhubarb Lip Sync's JSON export: {"metadata": {...}, "mouthCues": [{"start": 0.00,
// "end": 0.05, "value": "X"}, ...]}, or a bare array of cues (as tools that
// re-save Rhubarb's cues write it). Other keys are ignored. Small gaps
// between cues are kept as gaps.
PhonemeTrack parse_rhubarb_json(std::string_view text, const std::string& file);

// Rhubarb's TSV export: "seconds<TAB>shape" per line (spaces also accepted),
// each the start of a shape that lasts until the next line's time. The last
// line has no duration of its own (Rhubarb writes the end time with X there):
// it ends the previous cue and sets duration_s, and is not a segment.
PhonemeTrack parse_rhubarb_tsv(std::string_view text, const std::string& file);

// A Praat TextGrid, long or short text format, UTF-8 (BOM optional) or UTF-16
// with a BOM. Only interval tiers count. `tier_name` empty picks, ignoring case,
// a tier named phones, phone, phonemes, segments or PhonAlign (SPPAS), or ending
// in " - phones" (MFA, several speakers); else the only interval tier.
PhonemeTrack parse_textgrid(std::string_view text, const std::string& file,
                            std::string_view tier_name = {});

}  // namespace facectl
