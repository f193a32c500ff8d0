#pragma once

#include <array>
#include <string>

#include "control/command/face_layout.hpp"
#include "firmware-host/config/face_pose.hpp"

namespace facectl {

// The 15 MPEG-4 visemes (0 none, 1 p/b/m .. 14 U) as mouth poses in face-signal
// terms, loaded from YAML (config/fap/visemes.yaml):
//   visemes:
//     p_b_m: { index: 1, muscles: { orbicularis_oris: 0.35 }, mandible: { pitch_deg: 0 } }
// Every index 0..14 must appear exactly once.
class VisemeTable {
 public:
  static constexpr int kCount = 15;

  static VisemeTable load(const std::string& path, const FaceLayout& layout);

  const FacePose& pose(int index) const { return poses_.at(static_cast<std::size_t>(index)); }
  const std::string& name(int index) const { return names_.at(static_cast<std::size_t>(index)); }

 private:
  std::array<FacePose, kCount> poses_{};
  std::array<std::string, kCount> names_{};
};

}  // namespace facectl
