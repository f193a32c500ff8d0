// The one exception type for unusable input files: its message names file:line
// (and column when known), what was expected and what was found.
#pragma once

#include <stdexcept>
#include <string>

namespace facectl::face {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, int column, const std::string& what)
      : std::runtime_error(file + ":" + std::to_string(line) +
                           (column > 0 ? ":" + std::to_string(column) : std::string()) + ": " +
                           what) {}
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace facectl::face
