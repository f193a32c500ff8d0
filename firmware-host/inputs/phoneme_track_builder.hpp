// Shared by the phoneme parsers: error messages and the checks every segment
// must pass whatever the format.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_set>
#include <utility>

#include "firmware-host/inputs/phoneme_track.hpp"

namespace facectl {

class PhonemeTrackBuilder {
 public:
  explicit PhonemeTrackBuilder(std::string file) : file_(std::move(file)) {}

  // Throws ConfigError "file:line: [key: ]expected ..., found ...".
  [[noreturn]] void fail(int line, std::string_view key, std::string_view expected,
                         std::string_view found) const;
  // A time that is finite, >= 0 and within kMaxShowSeconds.
  void check_time(double t, int line, std::string_view key, std::string_view found) const;
  // Appends a segment after checking end >= start and that it starts no
  // earlier than the previous end. viseme < 0 is noted (the first
  // kMaxUnknownNotes labels, then a count) and stored as 0. Segments shorter
  // than kMinSegmentSeconds are counted and skipped; more than
  // kMaxPhonemeSegments is an error.
  void add(double start, double end, std::string label, int viseme, int line,
           std::string_view key = {});
  double last_end() const { return track_.segments.empty() ? 0.0 : track_.segments.back().end_s; }
  PhonemeTrack finish(double duration_s);

 private:
  std::string file_;  // a copy: a builder may outlive the caller's string
  PhonemeTrack track_;
  std::unordered_set<std::string> unknown_;  // labels noted as unknown
  long empty_ = 0;                           // segments skipped for no length
};

inline constexpr double kMinSegmentSeconds = 1e-4;
// 500 000 segments: about 14 hours of speech at 10 phones a second.
inline constexpr std::size_t kMaxPhonemeSegments = 500'000;
inline constexpr std::size_t kMaxUnknownNotes = 20;

// A quoted, shortened value for "found ...".
std::string quote_found(std::string_view s);

}  // namespace facectl
