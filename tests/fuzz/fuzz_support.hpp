// Shared by the libFuzzer targets of tests/fuzz (docs/FUZZING.md).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "firmware-host/config/expression_library.hpp"
#include "firmware-host/config/head_config.hpp"

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

// The shipped default head and expression library, loaded once: what the
// parsers that resolve names against a head (rig, show, expressions) get.
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

}  // namespace facectl::fuzz
