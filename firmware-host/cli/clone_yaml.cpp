#include "firmware-host/cli/clone_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "control/units.hpp"
#include "facectl/face/yaml_emit.hpp"

namespace facectl {
namespace {

using face::YamlName;
using face::YamlNumber;
using face::YamlScaled;
using Y = YAML::Emitter;

bool has(const std::vector<std::string>& keys, const std::string& k) {
  return std::find(keys.begin(), keys.end(), k) != keys.end();
}

// One flow mapping of the pose, `{muscles: {..}, mandible: {..}, rigid: {..}}`: the keys
// in `keep` plus any non-zero; a group with neither is left out.
void pose_flow(Y& y, const face::Expression& e, const face::HeadSpec& head,
               const std::vector<std::string>& keep) {
  auto shown = [&](double v, const std::string& key) { return v != 0 || has(keep, key); };
  std::vector<std::size_t> muscles;
  for (std::size_t i = 0; i < head.commanded.size(); ++i)
    if (shown(e.contractions[i], head.commanded[i])) muscles.push_back(i);
  if (!muscles.empty()) {
    y << YAML::Key << "muscles" << YAML::Value << YAML::BeginMap;
    for (const std::size_t i : muscles)
      y << YAML::Key << YamlName{head.commanded[i]} << YAML::Value << YamlNumber{e.contractions[i]};
    y << YAML::EndMap;
  }
  // The file's units, each written so that the reader's conversion gives back the SI value.
  const struct {
    const char* key;
    double si, si_per_unit;
  } jaw[] = {{"pitch_deg", e.jaw.pitch_rad, kDeg},
             {"yaw_deg", e.jaw.yaw_rad, kDeg},
             {"protrusion_mm", e.jaw.protrusion_m, 1e-3}};
  if (std::any_of(std::begin(jaw), std::end(jaw),
                  [&](const auto& j) { return shown(j.si, j.key); })) {
    y << YAML::Key << "mandible" << YAML::Value << YAML::BeginMap;
    for (const auto& j : jaw)
      if (shown(j.si, j.key))
        y << YAML::Key << j.key << YAML::Value << YamlScaled{j.si, j.si_per_unit};
    y << YAML::EndMap;
  }
  const std::string lids[2] = {"eyelid_closure_l", "eyelid_closure_r"};
  if (shown(e.eyelid_closure[0], lids[0]) || shown(e.eyelid_closure[1], lids[1])) {
    y << YAML::Key << "rigid" << YAML::Value << YAML::BeginMap;
    for (int side = 0; side < 2; ++side)
      if (shown(e.eyelid_closure[side], lids[side]))
        y << YAML::Key << lids[side] << YAML::Value << YamlNumber{e.eyelid_closure[side]};
    y << YAML::EndMap;
  }
}

void begin(Y& y, const std::string& comment, const char* key) {
  y << YAML::Comment(comment) << YAML::Newline << YAML::BeginMap << YAML::Key << key << YAML::Value
    << YAML::BeginMap;
}

}  // namespace

std::string library_yaml(const std::vector<face::Expression>& poses, const face::HeadSpec& head,
                         const std::vector<face::PoseSequence>& sequences,
                         const std::string& comment) {
  Y y;
  begin(y, comment, "expressions");
  for (const face::Expression& e : poses) {
    y << YAML::Key << YamlName{e.name} << YAML::Value << YAML::Flow << YAML::BeginMap;
    pose_flow(y, e, head, {});
    y << YAML::EndMap;
  }
  y << YAML::EndMap;
  if (!sequences.empty()) {
    y << YAML::Key << "sequences" << YAML::Value << YAML::BeginMap;
    for (const face::PoseSequence& s : sequences) {
      y << YAML::Key << YamlName{s.name} << YAML::Value << YAML::Flow << YAML::BeginMap;
      y << YAML::Key << "period_s" << YAML::Value << YamlNumber{s.period_s};
      y << YAML::Key << "poses" << YAML::Value << YAML::BeginSeq;
      for (const std::string& p : s.poses) y << YamlName{p};
      y << YAML::EndSeq << YAML::EndMap;
    }
    y << YAML::EndMap;
  }
  y << YAML::EndMap;
  return face::emitted(y);
}

std::string visemes_yaml(const std::vector<VisemePose>& visemes,
                         const std::vector<face::Expression>& cloned, const face::HeadSpec& head,
                         const std::string& comment) {
  Y y;
  begin(y, comment, "visemes");
  for (std::size_t i = 0; i < visemes.size(); ++i) {
    const VisemePose& v = visemes[i];
    y << YAML::Key << YamlName{v.pose.name} << YAML::Value << YAML::Flow << YAML::BeginMap;
    y << YAML::Key << "index" << YAML::Value << v.index;
    if (!v.phonemes.empty())
      y << YAML::Key << "phonemes" << YAML::Value << YAML::DoubleQuoted << v.phonemes;
    pose_flow(y, cloned[i], head, v.set_keys);
    y << YAML::EndMap;
  }
  y << YAML::EndMap << YAML::EndMap;
  return face::emitted(y);
}

}  // namespace facectl
