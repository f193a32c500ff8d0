// The files `facectl face clone` writes: the cloned library and visemes, in the formats
// load_expression_library() and the viseme loader read.
#pragma once

#include <string>
#include <vector>

#include "facectl/face/expression_library.hpp"
#include "firmware-host/cli/viseme_poses.hpp"

namespace facectl {

// `comment` (lines, without '#') heads the file; `sequences` are copied. Values are
// written so that the loaders read back exactly the commands given (yaml_emit.hpp).
std::string library_yaml(const std::vector<face::Expression>& poses, const face::HeadSpec& head,
                         const std::vector<face::PoseSequence>& sequences,
                         const std::string& comment);
// Each viseme's index, phonemes and the keys it set, with the values of `cloned[i]`.
std::string visemes_yaml(const std::vector<VisemePose>& visemes,
                         const std::vector<face::Expression>& cloned, const face::HeadSpec& head,
                         const std::string& comment);

}  // namespace facectl
