// Shared by the input tests: the default head and its retargeting table,
// loaded once per test binary.
#pragma once

#include <string>

#include "firmware-host/config/head_config.hpp"
#include "firmware-host/inputs/retarget_table.hpp"

namespace facectl::testing {

inline const std::string kDefaultHeadDir =
    std::string(FACECTL_SOURCE_DIR) + "/config/heads/default";

inline const HeadConfig& default_head_config() {
  static const HeadConfig h = load_head_config(kDefaultHeadDir + "/head.yaml");
  return h;
}

inline const RetargetTable& default_retarget() {
  static const RetargetTable t =
      RetargetTable::load(kDefaultHeadDir + "/retarget.yaml", default_head_config());
  return t;
}

}  // namespace facectl::testing
