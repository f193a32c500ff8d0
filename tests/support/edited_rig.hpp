#pragma once

#include <string>

#include "tests/support/temp_file.hpp"
#include "tests/support/text_files.hpp"

namespace facectl::testing {

// A shipped rig with text edits, in a temporary file. A broken rig a test
// needs is the shipped rig plus the one edit that breaks it, so it follows
// every other change to the rig instead of drifting from it as a copy would.
class EditedRig {
 public:
  // `shipped`: a path under the source tree, e.g. "config/rigs/hobby.yaml".
  explicit EditedRig(const std::string& shipped) : text_(read_text(source_path(shipped))) {}

  // Replaces `from`, which must occur exactly once (replaced_once).
  EditedRig& replace(const std::string& from, const std::string& to) {
    text_ = replaced_once(text_, from, to);
    return *this;
  }

  // Writes the rig as it stands; the file lives as long as the returned object.
  TempFile write() const { return TempFile(text_, ".yaml"); }

 private:
  std::string text_;
};

}  // namespace facectl::testing
