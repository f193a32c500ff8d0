#include "firmware-host/inputs/phoneme_track.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/inputs/phoneme_track_builder.hpp"

namespace facectl {

std::string quote_found(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::size_t cut = std::min(kMax, s.size());
  // Not inside a UTF-8 character: back up over its continuation bytes.
  while (cut < s.size() && cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
  std::string out = "'";
  out += s.substr(0, cut);
  if (s.size() > cut) out += "...";
  return out + "'";
}

void PhonemeTrackBuilder::fail(int line, std::string_view key, std::string_view expected,
                               std::string_view found) const {
  std::string msg = file_ + ":" + std::to_string(line) + ": ";
  if (!key.empty()) msg.append(key).append(": ");
  msg.append("expected ").append(expected).append(", found ").append(found);
  throw ConfigError(msg);
}

void PhonemeTrackBuilder::check_time(double t, int line, std::string_view key,
                                     std::string_view found) const {
  if (!std::isfinite(t) || t < 0.0 || t > kMaxShowSeconds) {
    fail(line, key, "a time in seconds from 0 to " + std::to_string(int(kMaxShowSeconds)), found);
  }
}

void PhonemeTrackBuilder::add(double start, double end, std::string label, int viseme, int line,
                              std::string_view key) {
  char buf[96];
  if (end < start) {
    std::snprintf(buf, sizeof buf, "%.6g s before its start %.6g s", end, start);
    fail(line, key, "an end no earlier than the start", buf);
  }
  const double prev = last_end();
  if (start < prev - kSegmentOverlapTolerance) {
    std::snprintf(buf, sizeof buf, "a start of %.6g s before the previous end %.6g s", start, prev);
    fail(line, key, "segments in time order, not overlapping", buf);
  }
  start = std::max(start, prev);
  end = std::max(end, start);
  // A segment of no length shows nothing, and would seal the lips for an
  // instant if it were a closure.
  if (end - start < kMinSegmentSeconds) {
    ++empty_;
    return;
  }
  if (track_.segments.size() >= kMaxPhonemeSegments) {
    fail(line, key, "at most " + std::to_string(kMaxPhonemeSegments) + " segments", "more");
  }
  if (viseme < 0) {
    viseme = kVisemeNone;
    if (unknown_.insert(label).second) {
      if (unknown_.size() <= kMaxUnknownNotes) {
        track_.notes.push_back(file_ + ":" + std::to_string(line) + ": unknown phone " +
                               quote_found(label) + " read as silence (viseme 0)");
      }
    }
  }
  track_.segments.push_back({start, end, std::move(label), viseme, line});
}

PhonemeTrack PhonemeTrackBuilder::finish(double duration_s) {
  track_.duration_s = std::max(duration_s, last_end());
  if (unknown_.size() > kMaxUnknownNotes) {
    track_.notes.push_back(std::to_string(unknown_.size() - kMaxUnknownNotes) +
                           " more unknown phones read as silence");
  }
  if (empty_ > 0) {
    track_.notes.push_back("skipped " + std::to_string(empty_) + " segments shorter than 0.1 ms");
  }
  return std::move(track_);
}

}  // namespace facectl
