#include "firmware-host/config/face_pose.hpp"

#include <string>
#include <vector>

namespace facectl {

void FacePose::apply_to(std::array<double, kMaxFaceSignals>& base) const {
  for (std::size_t i = 0; i < kMaxFaceSignals; ++i) {
    if (set[i]) base[i] = values[i];
  }
}

void FacePose::blend_into(std::array<double, kMaxFaceSignals>& base, double weight) const {
  for (std::size_t i = 0; i < kMaxFaceSignals; ++i) {
    if (set[i]) base[i] += weight * (values[i] - base[i]);
  }
}

namespace {

void set_value(FacePose& pose, std::size_t index, const ConfigNode& value, const SignalInfo& info) {
  const double si = value.number() * yaml_to_si(info.kind);
  if (si < info.domain_min || si > info.domain_max) {
    const double lo = info.domain_min / yaml_to_si(info.kind);
    const double hi = info.domain_max / yaml_to_si(info.kind);
    value.fail("a value of " + info.name + " in [" + std::to_string(lo) + ", " +
               std::to_string(hi) + "]");
  }
  pose.values[index] = si;
  pose.set[index] = true;
}

}  // namespace

FacePose parse_pose(const ConfigNode& node, const FaceLayout& layout,
                    std::initializer_list<std::string_view> extra_keys) {
  std::vector<std::string> allowed = {"muscles", "mandible", "rigid"};
  for (auto k : extra_keys) allowed.emplace_back(k);
  node.expect_keys(allowed);
  FacePose pose;

  if (auto muscles = node.get("muscles")) {
    for (const auto& [name, value] : muscles->entries()) {
      const auto index = layout.find(name);
      if (!index || *index >= layout.muscle_count()) {
        value.fail("a muscle of this head", "unknown muscle '" + name + "'");
      }
      set_value(pose, *index, value, layout.signal(*index));
    }
  }
  if (auto mandible = node.get("mandible")) {
    mandible->expect_keys({"pitch_deg", "yaw_deg", "protrusion_mm"});
    if (auto v = mandible->get("pitch_deg")) {
      set_value(pose, layout.jaw_pitch(), *v, layout.signal(layout.jaw_pitch()));
    }
    if (auto v = mandible->get("yaw_deg")) {
      set_value(pose, layout.jaw_yaw(), *v, layout.signal(layout.jaw_yaw()));
    }
    if (auto v = mandible->get("protrusion_mm")) {
      set_value(pose, layout.jaw_protrusion(), *v, layout.signal(layout.jaw_protrusion()));
    }
  }
  if (auto rigid = node.get("rigid")) {
    for (const auto& [key, value] : rigid->entries()) {
      const auto index = layout.find_yaml_key(key);
      const bool matched = index && *index > layout.jaw_protrusion();
      if (matched) set_value(pose, *index, value, layout.signal(*index));
      if (!matched) {
        value.fail("a rigid DOF key such as eye_yaw_l_deg, eyelid_closure_l or neck_pan_deg",
                   "unknown key '" + key + "'");
      }
    }
  }
  return pose;
}

}  // namespace facectl
