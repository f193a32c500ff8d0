// The files of `facectl face clone`: the viseme table read as face-model poses, and the
// cloned library, visemes and report written in the formats they were read in.
#pragma once

#include <string>
#include <vector>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/motion_clone.hpp"

namespace facectl {

// One viseme of config/fap/visemes.yaml: its pose (unset signals at 0, the neutral face)
// and what the file says besides, kept for the copy.
struct VisemePose {
  face::Expression pose;
  long index = 0;
  std::string phonemes;
  std::vector<std::string> set_keys;  // muscle names, pitch_deg.., eyelid_closure_l.. it sets
};

// Throws ConfigError naming file:line:column (the face-signal loader's checks).
std::vector<VisemePose> load_viseme_poses(const std::string& path, const face::HeadSpec& head);

// The jaw ranges of head.yaml's mandible_envelope, the design limits where it is silent.
face::JawBounds head_jaw_bounds(const face::HeadSpec& head);

// YAML loadable by load_expression_library() / the viseme loader; `sequences` copied.
std::string library_yaml(const std::vector<face::Expression>& poses, const face::HeadSpec& head,
                         const std::vector<face::PoseSequence>& sequences,
                         const std::string& header);
std::string visemes_yaml(const std::vector<VisemePose>& visemes,
                         const std::vector<face::Expression>& cloned, const face::HeadSpec& head,
                         const std::string& header);

struct CloneReportRow {
  std::string kind;  // "expressions" or "visemes"
  face::ClonedPose result;
};
std::string clone_report_json(const std::vector<CloneReportRow>& rows);

}  // namespace facectl
