// The JSON report of `facectl face clone --report`: per pose, the errors of the plain
// copy and of the result, and the refinement's counts.
#pragma once

#include <string>
#include <vector>

#include "facectl/face/motion_clone.hpp"

namespace facectl {

struct CloneReportRow {
  std::string kind;  // "expressions" or "visemes"
  face::ClonedPose result;
};
std::string clone_report_json(const std::vector<CloneReportRow>& rows);

}  // namespace facectl
