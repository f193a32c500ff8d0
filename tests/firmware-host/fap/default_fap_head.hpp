// The default head's FAP mapping, built once per test binary.
#pragma once

#include <string>

#include "firmware-host/config/expression_library.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/fap/fap_mapping.hpp"

namespace facectl::testing {

struct DefaultFapHead {
  HeadConfig head;
  ExpressionLibrary expressions;
  FapMapping mapping;
};

inline const DefaultFapHead& default_fap_head() {
  static const DefaultFapHead h = [] {
    const std::string src = FACECTL_SOURCE_DIR;
    HeadConfig head = load_head_config(src + "/config/heads/default/head.yaml");
    ExpressionLibrary lib =
        ExpressionLibrary::load(src + "/config/expressions/library.yaml", head.layout);
    FapMapping mapping = load_fap_mapping(head, lib, src + "/config/fap/visemes.yaml");
    return DefaultFapHead{std::move(head), std::move(lib), std::move(mapping)};
  }();
  return h;
}

// One frame of FAP text: the mask line for `values` (FAP number -> value
// fields) and the values line.
std::string fap_frame_text(long number, const std::vector<std::pair<int, std::string>>& values);

}  // namespace facectl::testing
