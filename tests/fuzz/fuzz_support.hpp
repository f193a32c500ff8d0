// Shared by the libFuzzer targets of tests/fuzz (docs/FUZZING.md).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "firmware-host/config/config_node.hpp"
#include "tests/support/default_head.hpp"

namespace facectl::fuzz {

// The parsers under test read files: each input is written to this process's
// own file (one per target and process, so parallel jobs do not collide) and
// the real loader reads it back, as `facectl` would.
class InputFile {
 public:
  explicit InputFile(const std::string& suffix)
      : path_("/tmp/facectl-fuzz-" + std::to_string(::getpid()) + suffix) {}
  ~InputFile() { std::remove(path_.c_str()); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::ofstream(path_, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path_;
  }

 private:
  std::string path_;
};

// Loads the input as a YAML file with `load`; the documented error, a
// ConfigError naming file:line:column, is an accepted outcome.
template <class Load>
int load_yaml(const std::uint8_t* data, std::size_t size, const Load& load) {
  static InputFile file(".yaml");  // one per target: each passes its own lambda
  try {
    load(file.write(data, size));
  } catch (const ConfigError&) {
  }
  return 0;
}

}  // namespace facectl::fuzz
