#pragma once

#include <array>
#include <bitset>

#include "control/capacity.hpp"
#include "control/command/face_layout.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// A (partial) face pose as written in YAML: values in SI, plus which signals it sets.
struct FacePose {
  std::array<double, kMaxFaceSignals> values{};
  std::bitset<kMaxFaceSignals> set;

  // Writes the set values over `base`.
  void apply_to(std::array<double, kMaxFaceSignals>& base) const;
  // base + weight * (this - base) for the set values.
  void blend_into(std::array<double, kMaxFaceSignals>& base, double weight) const;
};

// Parses a pose block:
//   muscles:  { zygomaticus_major_l: 0.8, ... }          contraction 0..1
//   mandible: { pitch_deg: 5, yaw_deg: 0, protrusion_mm: 2 }
//   rigid:    { eye_yaw_l_deg: 10, eyelid_closure_l: 1, neck_pan_deg: -20 }
// `extra_keys` are other keys the caller allows in the same mapping.
FacePose parse_pose(const ConfigNode& node, const FaceLayout& layout,
                    std::initializer_list<std::string_view> extra_keys = {});

}  // namespace facectl
