#include "firmware-host/inputs/mediapipe_blendshapes.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/inputs/json_input.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

using nlohmann::json;

constexpr double kDefaultFrameS = 1.0 / 30.0;
// What MediaPipe's APIs and the tools saving them call a category's name:
// JavaScript, Python, and the savers' own (V-Sekai's labeler: name, label).
constexpr const char* kNameKeys[] = {"categoryName", "category_name", "name", "label"};

struct Reader {
  const std::string& file;
  long clamped = 0;
  long unknown = 0;

  [[noreturn]] void fail(const std::string& where, const std::string& expected,
                         const json& found) const {
    // Lists and objects by their size: dumping one could cost as much as the file.
    std::string f = found.is_array()    ? "a list of " + std::to_string(found.size())
                    : found.is_object() ? "an object of " + std::to_string(found.size()) + " keys"
                                        : found.dump();
    if (f.size() > 60) f = f.substr(0, 57) + "...";
    // The JSON path from the top: "frames[3].jawOpen", "people[0][2].score".
    const std::string path = where.empty()     ? "(top level)"
                             : where[0] == '.' ? where.substr(1)
                                               : where;
    throw ConfigError(file + ": " + path + ": expected " + expected + ", found " + f);
  }

  // A score is a number, or a number in a string (some savers write
  // "0.83830165863037109375" to keep every digit).
  void score(const std::string& where, const std::string& name, const json& value,
             ArkitFrame& frame) {
    double s = 0;
    if (value.is_number()) {
      s = value.get<double>();
    } else if (!value.is_string() || !parse_number(value.get<std::string>(), s)) {
      fail(where, "a score (a number)", value);
    }
    if (!std::isfinite(s) || s < -0.5 || s > 1.5) fail(where, "a score in 0..1", value);
    const auto k = find_arkit(name);
    if (!k) {
      unknown += name != "_neutral";
      return;
    }
    clamped += (s < 0 || s > 1);
    frame.weights[*k] = std::clamp(s, 0.0, 1.0);
  }

  // A frame's blendshapes: a list of categories or an object of scores.
  void categories(const std::string& where, const json& j, ArkitFrame& frame) {
    if (j.is_object()) {
      for (const auto& [name, value] : j.items()) score(where + "." + name, name, value, frame);
      return;
    }
    if (!j.is_array()) fail(where, "a list of blendshape categories", j);
    for (std::size_t i = 0; i < j.size(); ++i) {
      const std::string w = where + "[" + std::to_string(i) + "]";
      const json& c = j[i];
      if (!c.is_object()) fail(w, "a category {\"categoryName\": ..., \"score\": ...}", c);
      const json* name = nullptr;
      for (const char* key : kNameKeys) {
        if (!name && c.contains(key)) name = &c[key];
      }
      if (!name || !name->is_string()) {
        fail(w, "a category name (categoryName, category_name, name or label)", c);
      }
      if (!c.contains("score")) fail(w, "a score", c);
      score(w + ".score", name->get<std::string>(), c["score"], frame);
    }
  }

  static bool is_category_list(const json& j) {
    if (!j.is_array() || j.empty() || !j[0].is_object()) return false;
    return std::any_of(std::begin(kNameKeys), std::end(kNameKeys),
                       [&](const char* key) { return j[0].contains(key); });
  }

  struct FrameInfo {
    std::optional<double> t;  // s, when the frame has a time
    bool face = true;         // false: the frame lists no face
  };

  // One frame.
  FrameInfo frame(const std::string& where, const json& j, ArkitFrame& out) {
    if (is_category_list(j)) {
      categories(where, j, out);
      return {};
    }
    if (!j.is_object()) fail(where, "a frame of blendshapes", j);
    const json* shapes = nullptr;
    std::string key_used;
    for (const char* key : {"blendshapes", "faceBlendshapes", "face_blendshapes", "people"}) {
      if (j.contains(key)) {
        shapes = &j[key];
        key_used = key;
      }
    }
    if (!shapes) {  // an object of scores
      categories(where, j, out);
      return {};
    }
    // Per face: [[...categories...], ...]; the first face is the performer.
    // An empty list of faces is a frame where the tracker found none.
    FrameInfo info;
    if (shapes->is_array() && shapes->empty()) {
      info.face = false;
    } else if (shapes->is_array() && (*shapes)[0].is_array()) {
      categories(where + "." + key_used + "[0]", (*shapes)[0], out);
    } else {
      categories(where + "." + key_used, *shapes, out);
    }
    for (const auto& [key, scale] :
         {std::pair{"timestamp_ms", 1e-3}, std::pair{"timestampMs", 1e-3}, std::pair{"t", 1.0},
          std::pair{"time", 1.0}}) {
      if (!j.contains(key)) continue;
      const json& v = j[key];
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0) {
        fail(where + "." + key, "a time >= 0", v);
      }
      info.t = v.get<double>() * scale;
      break;
    }
    return info;
  }
};

}  // namespace

ArkitCapture parse_mediapipe_blendshapes(std::string_view text, const std::string& file) {
  const json root = parse_json_input(text, file, "MediaPipe blendshapes JSON");
  Reader r{file};
  ArkitCapture capture;
  capture.producer = "MediaPipe blendshapes JSON";
  const json* frames = &root;
  std::string prefix;  // the frames' JSON path
  if (root.is_object() && root.contains("frames")) {
    frames = &root["frames"];
    prefix = "frames";
  }
  // A single frame is played as a list of one.
  const bool single = Reader::is_category_list(*frames) || frames->is_object();
  if (!single && (!frames->is_array() || frames->empty())) {
    r.fail(prefix, "a list of frames", *frames);
  }
  const std::size_t count = single ? 1 : frames->size();
  if (count > kMaxCaptureFrames) {
    r.fail(prefix, "at most " + std::to_string(kMaxCaptureFrames) + " frames", *frames);
  }
  std::optional<double> t0;
  long no_face = 0;
  double prev_t = 0;  // of the previous frame, with a face or not
  for (std::size_t i = 0; i < count; ++i) {
    const std::string where = single ? prefix : prefix + "[" + std::to_string(i) + "]";
    const json& item = single ? *frames : (*frames)[i];
    ArkitFrame f;
    const Reader::FrameInfo info = r.frame(where, item, f);
    if (info.t && !t0) t0 = *info.t;
    f.t = info.t ? *info.t - *t0 : static_cast<double>(i) * kDefaultFrameS;
    if (i > 0 && !(f.t > prev_t)) r.fail(where, "times that increase", json(f.t));
    prev_t = f.t;
    if (f.t > kMaxShowSeconds) {
      r.fail(where, "at most " + std::to_string(kMaxShowSeconds) + " s from the first frame",
             json(f.t));
    }
    if (!info.face) {
      ++no_face;
      continue;
    }
    capture.frames.push_back(f);
  }
  if (capture.frames.empty()) r.fail(prefix, "at least one frame with a face", *frames);
  if (no_face) {
    capture.notes.push_back("dropped " + std::to_string(no_face) + " frames without a face");
  }
  if (r.unknown)
    capture.notes.push_back("ignored " + std::to_string(r.unknown) +
                            " scores of unknown categories");
  if (r.clamped)
    capture.notes.push_back("clamped " + std::to_string(r.clamped) + " scores to 0..1");
  return capture;
}

}  // namespace facectl
