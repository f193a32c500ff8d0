#include "firmware-host/inputs/retarget_table.hpp"

#include <algorithm>
#include <cstdio>

#include "firmware-host/config/face_pose.hpp"

namespace facectl {
namespace {

std::string au_name(int au) {
  char text[8];
  std::snprintf(text, sizeof text, "AU%02d", au);
  return text;
}

// Which side a signal acts on: 'l', 'r' or 'm' (midline: no side suffix).
char side_of(std::string_view name) {
  if (name.size() > 2 && name[name.size() - 2] == '_') {
    if (name.back() == 'l' || name.back() == 'r') return name.back();
  }
  return 'm';
}

// A side-restricted entry keeps that side's signals and half of the midline
// ones, so that the Left and Right blendshapes together make the whole AU.
double side_weight(char keep, std::string_view signal) {
  const char s = side_of(signal);
  if (keep == 'm') return 1.0;
  if (s == 'm') return 0.5;
  return s == keep ? 1.0 : 0.0;
}

void add_scaled(std::array<double, kMaxFaceSignals>& to, const FacePose& pose, double w) {
  for (std::size_t i = 0; i < kMaxFaceSignals; ++i) {
    if (pose.set.test(i)) to[i] += w * pose.values[i];
  }
}

}  // namespace

int parse_action_unit_key(std::string_view key) {
  if (key.size() < 3 || key.size() > 4 || key[0] != 'A' || key[1] != 'U') return -1;
  int n = 0;
  for (char c : key.substr(2)) {
    if (c < '0' || c > '9') return -1;
    n = n * 10 + (c - '0');
  }
  return n >= 1 ? n : -1;
}

RetargetTable RetargetTable::load(const std::string& path, const HeadConfig& head) {
  const ConfigNode root = ConfigNode::load_file(path, "retarget");
  root.expect_keys({"retarget"});
  const ConfigNode node = root["retarget"];
  node.expect_keys({"action_units", "arkit", "unmapped"});
  RetargetTable t;
  t.layout_ = head.layout;
  const FaceLayout& layout = head.layout;

  std::map<int, std::string> au_where;
  for (const auto& [key, value] : node["action_units"].entries()) {
    const int au = parse_action_unit_key(key);
    if (au < 0) value.fail("an action unit key AU01..AU99", "'" + key + "'");
    if (t.au_set_.test(static_cast<std::size_t>(au))) {
      value.fail("each action unit once", "a second " + au_name(au));
    }
    add_scaled(t.au_[static_cast<std::size_t>(au)], parse_pose(value, layout), 1.0);
    t.au_set_.set(static_cast<std::size_t>(au));
    au_where[au] = value.where();
  }

  if (auto unmapped = node.get("unmapped")) {
    for (const auto& [key, value] : unmapped->entries()) {
      const int au = parse_action_unit_key(key);
      if (au < 0 && !find_arkit(key)) {
        value.fail("an action unit (AU05) or an ARKit blendshape (cheekPuff)", "'" + key + "'");
      }
      if ((au >= 0 && t.au_set_.test(static_cast<std::size_t>(au)))) {
        value.fail("an action unit that action_units does not map", key + ", which it maps");
      }
      t.unmapped_[au >= 0 ? au_name(au) : std::string(kArkitNames[*find_arkit(key)])] =
          value.string();
    }
  }

  for (const auto& [key, value] : node["arkit"].entries()) {
    const auto k = find_arkit(key);
    if (!k) value.fail("one of ARKit's 52 blendshape names (e.g. mouthSmileLeft)", "'" + key + "'");
    if (t.arkit_set_.test(*k)) value.fail("each blendshape once", "a second " + key);
    if (t.unmapped_.count(std::string(kArkitNames[*k]))) {
      value.fail("a blendshape that `unmapped` does not list", key + ", listed there too");
    }
    char keep = 'm';
    if (auto side = value.get("side")) {
      const std::string s = side->string();
      if (s != "left" && s != "right") side->fail("left or right", "'" + s + "'");
      keep = s == "left" ? 'l' : 'r';
    }
    auto& delta = t.arkit_[*k];
    if (auto facs = value.get("facs")) {
      for (const auto& [au_key, weight] : facs->entries()) {
        const int au = parse_action_unit_key(au_key);
        if (au < 0 || !t.au_set_.test(static_cast<std::size_t>(au))) {
          weight.fail("an action unit that action_units maps", "'" + au_key + "'");
        }
        const double w = weight.number_in(0.0, 1.0);
        for (std::size_t i = 0; i < layout.size(); ++i) {
          delta[i] +=
              w * side_weight(keep, layout.signal(i).name) * t.au_[static_cast<std::size_t>(au)][i];
        }
      }
    }
    add_scaled(delta, parse_pose(value, layout, {"facs", "side"}), 1.0);
    t.arkit_set_.set(*k);
  }
  std::string missing;
  for (std::size_t k = 0; k < kArkitCount; ++k) {
    if (!t.arkit_set_.test(k) && !t.unmapped_.count(std::string(kArkitNames[k]))) {
      missing += (missing.empty() ? "" : ", ") + std::string(kArkitNames[k]);
    }
  }
  if (!missing.empty()) {
    node["arkit"].fail("all 52 ARKit blendshapes in arkit or unmapped", "none for " + missing);
  }

  // head.yaml's facs lists and the table must tell the same anatomy.
  for (std::size_t m = 0; m < head.muscle_facs.size(); ++m) {
    for (int au : head.muscle_facs[m]) {
      if (!t.au_set_.test(static_cast<std::size_t>(au)) ||
          !(t.au_[static_cast<std::size_t>(au)][m] > 0)) {
        throw ConfigError(head.muscle_where[m] + ": muscle " + head.muscles[m] + " serves " +
                          au_name(au) + " (its facs list), but " + path + " has no " + au_name(au) +
                          " that contracts it");
      }
    }
  }
  for (const auto& [au, where] : au_where) {
    for (std::size_t m = 0; m < head.muscle_facs.size(); ++m) {
      const auto& list = head.muscle_facs[m];
      if (list.empty() || !(t.au_[static_cast<std::size_t>(au)][m] > 0)) continue;
      if (std::find(list.begin(), list.end(), au) == list.end()) {
        throw ConfigError(where + ": " + au_name(au) + " contracts " + head.muscles[m] +
                          ", whose facs list in " + head.muscle_where[m] + " does not name " +
                          std::to_string(au));
      }
    }
  }
  return t;
}

int RetargetTable::clamp(std::array<double, kMaxFaceSignals>& pose) const {
  int clamped = 0;
  for (std::size_t i = 0; i < layout_.size(); ++i) {
    const SignalInfo& s = layout_.signal(i);
    const double v = std::clamp(pose[i], s.domain_min, s.domain_max);
    clamped += v != pose[i];
    pose[i] = v;
  }
  return clamped;
}

int RetargetTable::add_arkit(std::span<const double, kArkitCount> weights,
                             std::array<double, kMaxFaceSignals>& pose) const {
  for (std::size_t k = 0; k < kArkitCount; ++k) {
    if (weights[k] == 0.0 || !arkit_set_.test(k)) continue;
    for (std::size_t i = 0; i < layout_.size(); ++i) pose[i] += weights[k] * arkit_[k][i];
  }
  return clamp(pose);
}

int RetargetTable::add_action_units(std::span<const double, kMaxActionUnit + 1> intensities,
                                    std::array<double, kMaxFaceSignals>& pose) const {
  for (std::size_t a = 0; a <= kMaxActionUnit; ++a) {
    if (intensities[a] == 0.0 || !au_set_.test(a)) continue;
    const double w = intensities[a] / kMaxAuIntensity;
    for (std::size_t i = 0; i < layout_.size(); ++i) pose[i] += w * au_[a][i];
  }
  return clamp(pose);
}

}  // namespace facectl
