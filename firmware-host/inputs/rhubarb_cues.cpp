// Rhubarb Lip Sync's JSON and TSV exports (parse_rhubarb_json, parse_rhubarb_tsv).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/inputs/json_input.hpp"
#include "firmware-host/inputs/phoneme_track.hpp"
#include "firmware-host/inputs/phoneme_track_builder.hpp"

namespace facectl {
namespace {

// The line of each element of the cue array: the value of the top-level key
// "mouthCues", or the top-level array itself. nlohmann::json keeps no
// positions, so this walks the (already valid) text once, skipping strings.
std::vector<int> cue_lines(std::string_view text, bool bare_array) {
  std::vector<int> lines;
  int depth = 0;
  int line = 1;
  int cue_depth = bare_array ? 1 : -1;  // depth inside the cue array
  bool expect_value = false;
  std::string_view last_string;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') continue;
    if (depth == cue_depth && expect_value && c != ']') {
      lines.push_back(line);
      expect_value = false;
    }
    if (c == '"') {
      const std::size_t begin = ++i;
      while (i < text.size() && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
      last_string = text.substr(begin, i - begin);
    } else if (c == '[' || c == '{') {
      ++depth;
      if (c == '[' && depth == 2 && !bare_array && last_string == "mouthCues") cue_depth = 2;
      if (depth == cue_depth) expect_value = true;
    } else if (c == ']' || c == '}') {
      if (depth == cue_depth) cue_depth = -1;
      --depth;
    } else if (c == ',' && depth == cue_depth) {
      expect_value = true;
    }
  }
  return lines;
}

// What was found, for a message: lists and objects by their size (dumping
// one could cost as much as the file).
std::string found_json(const nlohmann::json* j) {
  if (!j || j->is_null()) return "nothing";
  if (j->is_array()) return "a list of " + std::to_string(j->size());
  if (j->is_object()) return "an object of " + std::to_string(j->size()) + " keys";
  return quote_found(j->dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

}  // namespace

PhonemeTrack parse_rhubarb_json(std::string_view text, const std::string& file) {
  PhonemeTrackBuilder b(file);
  const nlohmann::json doc = parse_json_input(text, file, "a Rhubarb JSON file");
  const bool bare = doc.is_array();
  const auto cues_it = doc.is_object() ? doc.find("mouthCues") : doc.end();
  if (!bare && (cues_it == doc.end() || !cues_it->is_array())) {
    b.fail(1, {}, "a JSON object with a \"mouthCues\" array (Rhubarb's JSON export)",
           doc.is_object() ? (cues_it == doc.end() ? "no \"mouthCues\"" : found_json(&*cues_it))
                           : found_json(&doc));
  }
  const nlohmann::json& cues = bare ? doc : *cues_it;
  const std::vector<int> lines = cue_lines(text, bare);
  for (std::size_t i = 0; i < cues.size(); ++i) {
    const nlohmann::json& cue = cues[i];
    const int line = i < lines.size() ? lines[i] : 1;
    const std::string key = (bare ? "[" : "mouthCues[") + std::to_string(i) + "]";
    if (!cue.is_object())
      b.fail(line, key, "a cue {\"start\", \"end\", \"value\"}", found_json(&cue));
    double t[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      const char* name = k == 0 ? "start" : "end";
      const auto it = cue.find(name);
      const nlohmann::json* v = it == cue.end() ? nullptr : &*it;  // no copy: values may nest
      if (!v || !v->is_number()) {
        b.fail(line, key + "." + name, "a number of seconds", found_json(v));
      }
      t[k] = v->get<double>();
      b.check_time(t[k], line, key + "." + name, found_json(v));
    }
    const auto vit = cue.find("value");
    const nlohmann::json* v = vit == cue.end() ? nullptr : &*vit;
    const std::string shape = v && v->is_string() ? v->get<std::string>() : std::string();
    if (shape.size() != 1 || viseme_of_rhubarb_shape(shape[0]) < 0) {
      b.fail(line, key + ".value", "a mouth shape A-H or X", found_json(v));
    }
    b.add(t[0], t[1], shape, viseme_of_rhubarb_shape(shape[0]), line, key);
  }
  double duration = 0.0;
  if (!bare && doc.contains("metadata") && doc["metadata"].is_object()) {
    const auto d = doc["metadata"].find("duration");
    if (d != doc["metadata"].end() && d->is_number()) {
      const double v = d->get<double>();
      if (std::isfinite(v) && v >= 0.0 && v <= kMaxShowSeconds) duration = v;
    }
  }
  return b.finish(duration);
}

PhonemeTrack parse_rhubarb_tsv(std::string_view text, const std::string& file) {
  PhonemeTrackBuilder b(file);
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  struct Cue {
    double t;
    char shape;
    int line;
  };
  std::optional<Cue> open;  // the cue waiting for the next line's time
  int line = 0;
  double end_time = 0.0;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view row = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line;
    if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
    if (row.find_first_not_of(" \t") == std::string_view::npos) continue;
    const auto is_space = [](char c) { return c == ' ' || c == '\t'; };
    std::size_t i = 0;
    while (i < row.size() && is_space(row[i])) ++i;
    std::size_t j = i;
    while (j < row.size() && !is_space(row[j])) ++j;
    std::size_t k = j;
    while (k < row.size() && is_space(row[k])) ++k;
    std::size_t m = row.size();
    while (m > k && is_space(row[m - 1])) --m;
    double t = 0.0;
    const auto [p, ec] = std::from_chars(row.data() + i, row.data() + j, t);
    if (ec != std::errc() || p != row.data() + j || k == j || m - k != 1 ||
        viseme_of_rhubarb_shape(row[k]) < 0) {
      b.fail(line, {}, "'seconds<TAB>shape' with a shape A-H or X", quote_found(row));
    }
    b.check_time(t, line, {}, quote_found(row.substr(i, j - i)));
    if (open) {
      if (t < open->t) {
        b.fail(line, {}, "a time no earlier than the previous line's " + std::to_string(open->t),
               quote_found(row.substr(i, j - i)));
      }
      if (t > open->t) {
        b.add(open->t, t, std::string(1, open->shape), viseme_of_rhubarb_shape(open->shape),
              open->line);
      }
    }
    open = Cue{t, row[k], line};
    end_time = t;
  }
  return b.finish(end_time);
}

}  // namespace facectl
