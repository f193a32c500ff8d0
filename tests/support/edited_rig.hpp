#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tests/support/temp_file.hpp"

namespace facectl::testing {

// A shipped rig with text edits, in a temporary file. A broken rig a test
// needs is the shipped rig plus the one edit that breaks it, so it follows
// every other change to the rig instead of drifting from it as a copy would.
class EditedRig {
 public:
  // `shipped`: a path under the source tree, e.g. "config/rigs/hobby.yaml".
  explicit EditedRig(const std::string& shipped) {
    std::ifstream in(std::string(FACECTL_SOURCE_DIR) + "/" + shipped);
    if (!in) throw std::runtime_error("cannot read " + shipped);
    std::stringstream text;
    text << in.rdbuf();
    text_ = text.str();
  }

  // Replaces `from`, which must occur exactly once: an edit that no longer
  // matches the shipped rig fails the test instead of testing an unbroken rig.
  EditedRig& replace(const std::string& from, const std::string& to) {
    const auto at = text_.find(from);
    if (at == std::string::npos || text_.find(from, at + 1) != std::string::npos) {
      throw std::logic_error("the rig edit must match exactly once: " + from);
    }
    text_.replace(at, from.size(), to);
    return *this;
  }

  // Writes the rig as it stands; the file lives as long as the returned object.
  TempFile write() const { return TempFile(text_, ".yaml"); }

 private:
  std::string text_;
};

}  // namespace facectl::testing
