// Reading and editing the repository's text files in tests.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace facectl::testing {

// A path under the source tree, e.g. "config/rigs/default.yaml".
inline std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(FACECTL_SOURCE_DIR) / relative;
}

// The file's bytes; an unreadable file throws, so a test never edits nothing.
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `text` with `from`, which must occur exactly once, replaced by `to`: an edit
// that no longer matches the file it was written for fails the test instead of
// testing the unedited file.
inline std::string replaced_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos) {
    throw std::logic_error("the edit must match exactly once: " + from);
  }
  text.replace(at, from.size(), to);
  return text;
}

// `text` with every `from` replaced by `to`; there must be exactly `count`.
inline std::string replaced_all(std::string text, const std::string& from, const std::string& to,
                                std::size_t count) {
  std::size_t found = 0;
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
    ++found;
  }
  if (found != count) {
    throw std::logic_error("the edit must match " + std::to_string(count) + " times, found " +
                           std::to_string(found) + ": " + from);
  }
  return text;
}

}  // namespace facectl::testing
