#include "firmware-host/cli/viseme_poses.hpp"

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/face_pose.hpp"

namespace facectl {

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

}  // namespace facectl
