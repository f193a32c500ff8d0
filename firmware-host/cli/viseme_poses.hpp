// The viseme table (config/fap/visemes.yaml) read as face-model poses for `facectl face
// clone`, with what the file says besides, kept for the cloned copy.
#pragma once

#include <string>
#include <vector>

#include "facectl/face/expression_library.hpp"

namespace facectl {

// One viseme: its pose (unset signals at 0, the neutral face), index and phonemes.
struct VisemePose {
  face::Expression pose;
  long index = 0;
  std::string phonemes;
  std::vector<std::string> set_keys;  // muscle names, pitch_deg.., eyelid_closure_l.. it sets
};

// Throws ConfigError naming file:line:column (the face-signal loader's checks).
std::vector<VisemePose> load_viseme_poses(const std::string& path, const face::HeadSpec& head);

}  // namespace facectl
