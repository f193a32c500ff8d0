// The shipped default head and its expression library, loaded once per binary.
#pragma once

#include <string>

#include "firmware-host/config/expression_library.hpp"
#include "firmware-host/config/head_config.hpp"

namespace facectl::testing {

struct DefaultHead {
  HeadConfig head;
  ExpressionLibrary expressions;
};

inline const DefaultHead& default_head() {
  static const DefaultHead h = [] {
    const std::string src = FACECTL_SOURCE_DIR;
    HeadConfig head = load_head_config(src + "/config/heads/default/head.yaml");
    ExpressionLibrary lib =
        ExpressionLibrary::load(src + "/config/expressions/library.yaml", head.layout);
    return DefaultHead{std::move(head), std::move(lib)};
  }();
  return h;
}

}  // namespace facectl::testing
