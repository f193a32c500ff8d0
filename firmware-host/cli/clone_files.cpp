#include "firmware-host/cli/clone_files.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "control/units.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/face_pose.hpp"
#include "firmware-host/config/head_config.hpp"

namespace facectl {
namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", std::abs(v) < 1e-12 ? 0.0 : v);
  return b;
}

// A YAML double-quoted scalar, escaped by yaml-cpp.
std::string yaml_quoted(const std::string& text) {
  YAML::Emitter e;
  e << YAML::DoubleQuoted << text;
  return e.c_str();
}

bool has(const std::vector<std::string>& keys, const std::string& k) {
  return std::find(keys.begin(), keys.end(), k) != keys.end();
}

// `{ muscles: {..}, mandible: {..}, rigid: {..} }`: the keys in `keep` plus any non-zero.
std::string pose_flow(const face::Expression& e, const face::HeadSpec& head,
                      const std::vector<std::string>& keep) {
  std::vector<std::string> parts;
  std::string m;
  for (std::size_t i = 0; i < head.commanded.size(); ++i)
    if (e.contractions[i] != 0 || has(keep, head.commanded[i]))
      m += (m.empty() ? "" : ", ") + head.commanded[i] + ": " + num(e.contractions[i]);
  if (!m.empty()) parts.push_back("muscles: { " + m + " }");
  std::string j;
  auto jaw = [&](const char* key, double v) {
    if (v != 0 || has(keep, key)) j += (j.empty() ? "" : ", ") + std::string(key) + ": " + num(v);
  };
  jaw("pitch_deg", e.jaw.pitch_rad / kDeg);
  jaw("yaw_deg", e.jaw.yaw_rad / kDeg);
  jaw("protrusion_mm", e.jaw.protrusion_m * 1e3);
  if (!j.empty()) parts.push_back("mandible: { " + j + " }");
  std::string r;
  for (int side = 0; side < 2; ++side) {
    const std::string key = side == 0 ? "eyelid_closure_l" : "eyelid_closure_r";
    if (e.eyelid_closure[side] != 0 || has(keep, key))
      r += (r.empty() ? "" : ", ") + key + ": " + num(e.eyelid_closure[side]);
  }
  if (!r.empty()) parts.push_back("rigid: { " + r + " }");
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : ", ") + p;
  return out;
}

}  // namespace

std::vector<VisemePose> load_viseme_poses(const std::string& path, const face::HeadSpec& head) {
  const FaceLayout layout(head.commanded);
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"visemes"});
  std::vector<VisemePose> out;
  for (const auto& [name, node] : root["visemes"].entries()) {
    VisemePose v;
    v.index = node["index"].integer();
    if (auto p = node.get("phonemes")) v.phonemes = p->string();
    const FacePose pose = parse_pose(node, layout, {"index", "phonemes"});
    v.pose.name = name;
    v.pose.contractions.assign(head.commanded.size(), 0.0);
    for (std::size_t i = 0; i < layout.size(); ++i) {
      if (!pose.set[i]) continue;
      const double x = pose.values[i];
      const std::string& signal = layout.signal(i).name;
      if (i < layout.muscle_count()) {
        v.pose.contractions[i] = x;
        v.set_keys.push_back(signal);
      } else if (i == layout.jaw_pitch()) {
        v.pose.jaw.pitch_rad = x;
        v.set_keys.emplace_back("pitch_deg");
      } else if (i == layout.jaw_yaw()) {
        v.pose.jaw.yaw_rad = x;
        v.set_keys.emplace_back("yaw_deg");
      } else if (i == layout.jaw_protrusion()) {
        v.pose.jaw.protrusion_m = x;
        v.set_keys.emplace_back("protrusion_mm");
      } else if (signal == "eyelid_closure_l" || signal == "eyelid_closure_r") {
        v.pose.eyelid_closure[signal.back() == 'l' ? 0 : 1] = x;
        v.set_keys.push_back(signal);
      } else {
        node.fail("mouth and eyelid signals (the face model has no eyes or neck to clone)",
                  "'" + signal + "'");
      }
    }
    out.push_back(std::move(v));
  }
  return out;
}

face::JawBounds head_jaw_bounds(const face::HeadSpec& head) {
  face::JawBounds b = face::design_jaw_bounds();
  const HeadConfig config = load_head_config(head.dir + "/head.yaml");
  if (!config.envelope) return b;
  const EnvelopeSpec& e = *config.envelope;
  if (e.pitch) b.pitch_min = e.pitch->min, b.pitch_max = e.pitch->max;
  if (e.yaw) b.yaw_min = e.yaw->min, b.yaw_max = e.yaw->max;
  if (e.protrusion) b.protrusion_min = e.protrusion->min, b.protrusion_max = e.protrusion->max;
  return b;
}

std::string library_yaml(const std::vector<face::Expression>& poses, const face::HeadSpec& head,
                         const std::vector<face::PoseSequence>& sequences,
                         const std::string& header) {
  std::string out = header + "expressions:\n";
  for (const face::Expression& e : poses) {
    const std::string pose = pose_flow(e, head, {});
    out += "  " + e.name + ": " + (pose.empty() ? "{}" : "{ " + pose + " }") + "\n";
  }
  if (!sequences.empty()) {
    out += "sequences:\n";
    for (const face::PoseSequence& s : sequences) {
      std::string poses_list;
      for (const std::string& p : s.poses) poses_list += (poses_list.empty() ? "" : ", ") + p;
      out +=
          "  " + s.name + ": { period_s: " + num(s.period_s) + ", poses: [" + poses_list + "] }\n";
    }
  }
  return out;
}

std::string visemes_yaml(const std::vector<VisemePose>& visemes,
                         const std::vector<face::Expression>& cloned, const face::HeadSpec& head,
                         const std::string& header) {
  std::string out = header + "visemes:\n";
  for (std::size_t i = 0; i < visemes.size(); ++i) {
    const VisemePose& v = visemes[i];
    std::string line = "  " + v.pose.name + ": { index: " + std::to_string(v.index);
    if (!v.phonemes.empty()) line += ", phonemes: " + yaml_quoted(v.phonemes);
    const std::string pose = pose_flow(cloned[i], head, v.set_keys);
    if (!pose.empty()) line += ", " + pose;
    out += line + " }\n";
  }
  return out;
}

std::string clone_report_json(const std::vector<CloneReportRow>& rows) {
  auto error = [](const face::CloneError& e) {
    return nlohmann::ordered_json{
        {"rms_mm", e.rms_mm}, {"max_mm", e.max_mm}, {"percent", e.percent}};
  };
  nlohmann::ordered_json j = {{"expressions", nlohmann::ordered_json::object()},
                              {"visemes", nlohmann::ordered_json::object()}};
  for (const CloneReportRow& r : rows) {
    const face::ClonedPose& c = r.result;
    j[r.kind][c.pose.name] = {{"copy", error(c.copy)},
                              {"refined", error(c.refined)},
                              {"free_parameters", c.free_parameters},
                              {"iterations", c.iterations},
                              {"evaluations", c.evaluations},
                              {"settled", c.settled}};
  }
  return j.dump(2) + "\n";
}

}  // namespace facectl
