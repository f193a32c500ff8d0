#include "firmware-host/inputs/openface_csv.hpp"

#include <algorithm>
#include <optional>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

// "AU12_r" -> (12, 'r'); (-1, 0) for any other name.
std::pair<int, char> au_column(std::string_view name) {
  if (name.size() < 5 || name[name.size() - 2] != '_') return {-1, 0};
  const char kind = name.back();
  if (kind != 'r' && kind != 'c') return {-1, 0};
  return {parse_action_unit_key(name.substr(0, name.size() - 2)), kind};
}

struct Columns {
  std::size_t width = 0;
  std::optional<std::size_t> timestamp, confidence, success;
  std::vector<std::pair<std::size_t, int>> intensity, presence;  // (column, AU)
};

Columns read_header(std::string_view line, const std::string& file, int number) {
  Columns c;
  const auto names = split_fields(line, ',');
  c.width = names.size();
  std::array<bool, RetargetTable::kMaxActionUnit + 1> has_r{};
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == "timestamp") c.timestamp = i;
    if (names[i] == "confidence") c.confidence = i;
    if (names[i] == "success") c.success = i;
    const auto [au, kind] = au_column(names[i]);
    if (au < 0) continue;
    (kind == 'r' ? c.intensity : c.presence).push_back({i, au});
    if (kind == 'r') has_r[static_cast<std::size_t>(au)] = true;
  }
  // Presence counts only for AUs without an intensity column.
  std::erase_if(c.presence,
                [&](const auto& p) { return has_r[static_cast<std::size_t>(p.second)]; });
  if (!c.timestamp || !c.confidence || !c.success) {
    fail_at_line(file, number, "OpenFace's timestamp, confidence and success columns", line);
  }
  if (c.intensity.empty() && c.presence.empty())
    fail_at_line(file, number, "AUxx_r or AUxx_c columns", line);
  return c;
}

double field(const std::vector<std::string_view>& f, std::size_t i, const std::string& file,
             int line, const char* what) {
  double v;
  if (!parse_number(f[i], v)) fail_at_line(file, line, std::string(what) + " as a number", f[i]);
  return v;
}

}  // namespace

bool looks_like_openface_csv(std::string_view text) {
  const std::string_view first = first_line(text);
  return first.find("confidence") != std::string_view::npos &&
         first.find("success") != std::string_view::npos &&
         (first.find("AU01_r") != std::string_view::npos ||
          first.find("AU01_c") != std::string_view::npos);
}

OpenFaceCapture parse_openface_csv(std::string_view text, const std::string& file) {
  TextLines lines(text);
  std::string_view line;
  if (!lines.next(line)) fail_at_line(file, 1, "an OpenFace CSV header", "an empty file");
  const Columns c = read_header(line, file, lines.number());
  OpenFaceCapture capture;
  long held = 0;
  double t0 = 0;
  std::vector<std::string_view> f;
  while (next_csv_row(lines, c.width, file, f)) {
    if (capture.frames.size() >= kMaxCaptureFrames) {
      fail_at_line(file, lines.number(), "at most " + std::to_string(kMaxCaptureFrames) + " frames",
                   "more");
    }
    OpenFaceFrame frame;
    const double t = field(f, *c.timestamp, file, lines.number(), "timestamp");
    if (capture.frames.empty()) t0 = t;
    frame.t = t - t0;
    if (!capture.frames.empty() && !(frame.t > capture.frames.back().t)) {
      fail_at_line(file, lines.number(), "timestamps that increase", f[*c.timestamp]);
    }
    if (frame.t > kMaxShowSeconds) {
      fail_at_line(file, lines.number(),
                   "at most " + std::to_string(kMaxShowSeconds) + " s from the first frame",
                   f[*c.timestamp]);
    }
    const double confidence = field(f, *c.confidence, file, lines.number(), "confidence");
    const double success = field(f, *c.success, file, lines.number(), "success");
    if (success != 0 && success != 1)
      fail_at_line(file, lines.number(), "success 0 or 1", f[*c.success]);
    frame.tracked = success == 1 && confidence >= kMinOpenFaceConfidence;
    held += !frame.tracked;
    for (const auto& [col, au] : c.intensity) {
      const double v = field(f, col, file, lines.number(), "an AU intensity");
      // OpenFace's regressors leave 0..5 a little; far outside is not an intensity.
      if (v < -1 || v > 6) fail_at_line(file, lines.number(), "an AU intensity in 0..5", f[col]);
      frame.intensity[static_cast<std::size_t>(au)] = std::clamp(v, 0.0, 5.0);
    }
    for (const auto& [col, au] : c.presence) {
      const double v = field(f, col, file, lines.number(), "an AU presence");
      if (v != 0 && v != 1) fail_at_line(file, lines.number(), "an AU presence 0 or 1", f[col]);
      frame.intensity[static_cast<std::size_t>(au)] = v * kPresenceOnlyIntensity;
    }
    capture.frames.push_back(frame);
  }
  if (capture.frames.empty()) fail_at_line(file, lines.number(), "at least one frame", "none");
  if (held) {
    capture.notes.push_back("held " + std::to_string(held) +
                            " frames the tracker lost (success 0 or confidence below 0.8)");
  }
  return capture;
}

PoseTrack openface_pose_track(const OpenFaceCapture& capture, const RetargetTable& table,
                              const FaceLayout& layout,
                              const std::array<double, kMaxFaceSignals>& neutral,
                              std::vector<std::string>& notes) {
  PoseTrack track(layout.size());
  track.reserve(capture.frames.size() + 1);
  long clamped = 0;
  std::array<double, kMaxFaceSignals> last = neutral;  // before any tracked frame: rest
  double last_untracked_t = -1;
  for (const OpenFaceFrame& f : capture.frames) {
    if (!f.tracked) {
      last_untracked_t = f.t;
      continue;
    }
    // The held pose lasts until the last untracked frame of the run.
    if (last_untracked_t >= 0) {
      track.add(last_untracked_t, last);
      last_untracked_t = -1;
    }
    std::array<double, kMaxFaceSignals> pose = neutral;
    clamped += table.add_action_units(f.intensity, pose);
    track.add(f.t, pose);
    last = pose;
  }
  if (last_untracked_t >= 0 || track.empty()) track.add(std::max(last_untracked_t, 0.0), last);
  if (clamped > 0) {
    notes.push_back("clamped: " + std::to_string(clamped) +
                    " signal values summed past their range by the retargeting table");
  }
  std::string unmapped;
  for (int au = 1; au <= RetargetTable::kMaxActionUnit; ++au) {
    if (table.has_action_unit(au)) continue;
    const bool used = std::any_of(
        capture.frames.begin(), capture.frames.end(),
        [au](const auto& f) { return f.intensity[static_cast<std::size_t>(au)] > 0.0; });
    if (used) unmapped += (unmapped.empty() ? "AU" : ", AU") + std::to_string(au);
  }
  if (!unmapped.empty())
    notes.push_back("not shown by this head (retarget.yaml unmapped): " + unmapped);
  return track;
}

}  // namespace facectl
