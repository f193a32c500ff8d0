#include "firmware-host/verify/findings.hpp"

#include <algorithm>

namespace facectl::verify {

const char* to_string(Finding::Severity s) {
  switch (s) {
    case Finding::Severity::kFail:
      return "FAIL";
    case Finding::Severity::kWarn:
      return "warn";
    case Finding::Severity::kInfo:
      return "info";
  }
  return "?";
}

bool any_failure(const std::vector<Finding>& findings) {
  return std::any_of(findings.begin(), findings.end(),
                     [](const Finding& f) { return f.severity == Finding::Severity::kFail; });
}

}  // namespace facectl::verify
