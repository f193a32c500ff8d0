// The default head's FAP mapping, built once per test binary.
#pragma once

#include <string>

#include "firmware-host/fap/fap_mapping.hpp"
#include "tests/support/default_head.hpp"

namespace facectl::testing {

struct DefaultFapHead {
  HeadConfig head;
  ExpressionLibrary expressions;
  FapMapping mapping;
};

inline const DefaultFapHead& default_fap_head() {
  static const DefaultFapHead h = [] {
    const DefaultHead& base = default_head();
    FapMapping mapping = load_fap_mapping(
        base.head, base.expressions, std::string(FACECTL_SOURCE_DIR) + "/config/fap/visemes.yaml");
    return DefaultFapHead{base.head, base.expressions, std::move(mapping)};
  }();
  return h;
}

// One frame of FAP text: the mask line for `values` (FAP number -> value
// fields) and the values line.
std::string fap_frame_text(long number, const std::vector<std::pair<int, std::string>>& values);

}  // namespace facectl::testing
