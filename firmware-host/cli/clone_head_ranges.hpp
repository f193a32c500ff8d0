// The target head's command ranges for `facectl face clone`, from its head.yaml: the
// mandible envelope and the eyelid closure range.
#pragma once

#include "facectl/face/head_spec.hpp"
#include "facectl/face/motion_clone.hpp"

namespace facectl {

// o.jaw from head.yaml's mandible_envelope (the design limits where it is silent) and
// o.eyelid from its `rigid: eyelid_closure` (0..1 where it is silent). Throws ConfigError
// naming file:line:column for a malformed head.yaml.
void set_head_ranges(const face::HeadSpec& head, face::MotionCloneOptions& o);

}  // namespace facectl
