#pragma once

#include <string>
#include <vector>

namespace facectl::verify {

// One result of a check, for people and for JSON.
struct Finding {
  enum class Severity { kFail, kWarn, kInfo };
  Severity severity = Severity::kInfo;
  std::string check;    // e.g. "hardware range", "antagonists", "adversarial"
  std::string subject;  // actuator, constraint or bus
  std::string message;  // names the limit and the numbers
  std::string witness;  // an input that shows it, if any
};

const char* to_string(Finding::Severity s);
bool any_failure(const std::vector<Finding>& findings);

}  // namespace facectl::verify
