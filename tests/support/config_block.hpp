#pragma once

// Tests of one runtime-file block: parse it from text, and tell its error.
#include <functional>
#include <string>

#include "firmware-host/config/config_node.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl::testing {

// `parse` applied to the block `key:` whose body is `body` (indented lines),
// read from a file as the runtime file is, so errors name file:line:column.
template <typename Parse>
auto parse_block(const std::string& key, const std::string& body, Parse parse) {
  const TempFile f(key + ":\n" + body);
  return parse(ConfigNode::load_file(f.path(), "")[key]);
}

// The ConfigError `f` throws, or "accepted".
inline std::string config_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace facectl::testing
