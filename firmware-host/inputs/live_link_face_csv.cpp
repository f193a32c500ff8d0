#include "firmware-host/inputs/live_link_face_csv.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

struct Timecode {
  double seconds = 0;  // HH:MM:SS
  double frame = 0;    // FF plus the subframe
};

std::optional<Timecode> parse_timecode(std::string_view s) {
  const auto parts = split_fields(s, ':');
  if (parts.size() != 4) return std::nullopt;
  double h, m, sec, ff;
  if (!parse_number(parts[0], h) || !parse_number(parts[1], m) || !parse_number(parts[2], sec) ||
      !parse_number(parts[3], ff)) {
    return std::nullopt;
  }
  if (h < 0 || h >= 24 || m < 0 || m >= 60 || sec < 0 || sec >= 60 || ff < 0 || ff >= 60) {
    return std::nullopt;
  }
  return Timecode{h * 3600 + m * 60 + sec, ff};
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Column indices of what we read, from the header.
struct Columns {
  std::size_t timecode = 0;
  std::optional<std::size_t> count;
  std::array<std::size_t, kArkitCount> shapes{};
  std::optional<std::size_t> yaw, pitch, roll;
  std::size_t width = 0;
};

Columns read_header(std::string_view line, const std::string& file, int number) {
  const auto names = split_fields(line, ',');
  Columns c;
  c.width = names.size();
  std::array<bool, kArkitCount> seen{};
  bool timecode = false;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string n = lower(names[i]);
    if (n == "timecode") {
      c.timecode = i;
      timecode = true;
    } else if (n == "blendshapecount") {
      c.count = i;
    } else if (n == "headyaw") {
      c.yaw = i;
    } else if (n == "headpitch") {
      c.pitch = i;
    } else if (n == "headroll") {
      c.roll = i;
    } else if (auto k = find_arkit(names[i])) {
      if (seen[*k]) fail_at_line(file, number, "each blendshape column once", names[i]);
      seen[*k] = true;
      c.shapes[*k] = i;
    }
  }
  if (!timecode) fail_at_line(file, number, "a Timecode column", line);
  std::string missing;
  for (std::size_t k = 0; k < kArkitCount; ++k) {
    if (!seen[k]) missing += (missing.empty() ? "" : " ") + std::string(kArkitNames[k]);
  }
  if (!missing.empty())
    fail_at_line(file, number, "all 52 ARKit blendshape columns", "none for " + missing);
  return c;
}

}  // namespace

bool looks_like_live_link_face_csv(std::string_view text) {
  const std::string_view first = first_line(text);
  const std::string l = lower(first.substr(0, 40));
  return l.rfind("timecode,blendshapecount", 0) == 0;
}

ArkitCapture parse_live_link_face_csv(std::string_view text, const std::string& file) {
  TextLines lines(text);
  std::string_view line;
  if (!lines.next(line))
    fail_at_line(file, 1, "a header 'Timecode,BlendShapeCount,...'", "an empty file");
  const Columns c = read_header(line, file, lines.number());

  struct Row {
    Timecode tc;
    ArkitFrame frame;
    int line = 0;
  };
  std::vector<Row> rows;
  ArkitCapture capture;
  capture.producer = "Live Link Face CSV";
  long no_face = 0, repeated = 0, clamped = 0;
  double max_ff = 0;
  bool rolled_over = false;  // a row whose whole second follows the previous row's
  std::vector<std::string_view> f;
  while (next_csv_row(lines, c.width, file, f)) {
    const auto tc = parse_timecode(f[c.timecode]);
    if (!tc) fail_at_line(file, lines.number(), "a timecode HH:MM:SS:FF[.sub]", f[c.timecode]);
    double count = 0;
    if (c.count) {
      if (!parse_number(f[*c.count], count))
        fail_at_line(file, lines.number(), "a BlendShapeCount", f[*c.count]);
      if (count == 0) {  // the app found no face in this frame
        ++no_face;
        continue;
      }
    }
    Row row{*tc, {}, lines.number()};
    for (std::size_t k = 0; k < kArkitCount; ++k) {
      double w;
      const std::string_view field = f[c.shapes[k]];
      if (!parse_number(field, w))
        fail_at_line(file, lines.number(), std::string(kArkitNames[k]) + " as a number", field);
      // ARKit's solver overshoots a little; far outside 0..1 is not a weight.
      if (w < -0.5 || w > 1.5)
        fail_at_line(file, lines.number(), std::string(kArkitNames[k]) + " in 0..1", field);
      clamped += (w < 0 || w > 1);
      row.frame.weights[k] = std::clamp(w, 0.0, 1.0);
    }
    if (c.yaw && c.pitch && c.roll) {
      double* out[3] = {&row.frame.head_yaw, &row.frame.head_pitch, &row.frame.head_roll};
      const std::size_t cols[3] = {*c.yaw, *c.pitch, *c.roll};
      for (int i = 0; i < 3; ++i) {
        if (!parse_number(f[cols[i]], *out[i]) || std::abs(*out[i]) > M_PI) {
          fail_at_line(file, lines.number(), "a head rotation in radians (-pi..pi)", f[cols[i]]);
        }
      }
      row.frame.has_head = true;
    }
    if (rows.size() >= kMaxCaptureFrames) {
      fail_at_line(file, lines.number(), "at most " + std::to_string(kMaxCaptureFrames) + " frames",
                   "more");
    }
    max_ff = std::max(max_ff, tc->frame);
    rolled_over |= !rows.empty() && tc->seconds == rows.back().tc.seconds + 1;
    rows.push_back(row);
  }
  if (rows.empty()) fail_at_line(file, lines.number(), "at least one frame with a face", "none");

  // Only a file that crosses a second shows its timecode's rate; the app's is 60.
  double rate = 60;
  for (double r : {24.0, 25.0, 30.0, 48.0, 50.0, 60.0}) {
    if (rolled_over && max_ff < r) {
      rate = r;
      break;
    }
  }
  // Times from the first frame, compared as computed (the same arithmetic
  // for every row, so a repeated timecode gives the same time); a timecode
  // 12 h or more before the previous row's crossed midnight.
  const auto abs_time = [rate](const Timecode& tc) { return tc.seconds + tc.frame / rate; };
  const double t0 = abs_time(rows.front().tc);
  double day = 0;
  double prev = -1;  // the previous kept row's time from t0
  for (Row& r : rows) {
    double t = abs_time(r.tc) - t0 + day;
    if (prev >= 0 && t <= prev - 43200) {
      day += 86400;
      t += 86400;
    }
    if (prev >= 0 && t <= prev) {
      if (t < prev)
        fail_at_line(file, r.line, "timecodes that increase", std::to_string(prev - t) + " s back");
      ++repeated;
      continue;
    }
    if (t > kMaxShowSeconds) {
      fail_at_line(file, r.line, "a take of at most " + std::to_string(kMaxShowSeconds) + " s",
                   std::to_string(t) + " s");
    }
    prev = t;
    r.frame.t = t;
    capture.frames.push_back(r.frame);
  }
  if (no_face)
    capture.notes.push_back("dropped " + std::to_string(no_face) +
                            " rows without a face (BlendShapeCount 0)");
  if (repeated)
    capture.notes.push_back("dropped " + std::to_string(repeated) +
                            " rows repeating the previous timecode");
  if (clamped)
    capture.notes.push_back("clamped " + std::to_string(clamped) + " blendshape weights to 0..1");
  char rate_note[80];
  std::snprintf(rate_note, sizeof rate_note, "timecode read at %.0f frames per second", rate);
  capture.notes.push_back(rate_note);
  return capture;
}

}  // namespace facectl
