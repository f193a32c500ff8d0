// `facectl simulate` as a user runs it: the built binary in a child process,
// with outputs in a temporary folder.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "tests/support/text_files.hpp"

namespace facectl::testing {

// A folder that lives as long as this object.
class TempDir {
 public:
  TempDir() {
    std::string templ = "/tmp/facectl-simulate-XXXXXX";
    path_ = mkdtemp(templ.data());
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

struct ProcessResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs FACECTL_BINARY with `args` (no shell quoting needed: arguments are
// single-quoted), stdin closed. With `timeout_s`, coreutils' timeout ends a
// run that hangs (exit code 124), so that the test fails rather than waits.
inline ProcessResult run_facectl(const std::vector<std::string>& args,
                                 const std::filesystem::path& log, int timeout_s = 0) {
  std::string cmd = timeout_s > 0 ? "timeout -k 5 " + std::to_string(timeout_s) + " " : "";
  cmd += "'" + std::string(FACECTL_BINARY) + "'";
  for (const std::string& a : args) cmd += " '" + a + "'";
  cmd += " < /dev/null > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(log)};
}

// Every regular file under `dir` with its bytes, by path relative to `dir`.
inline std::map<std::string, std::string> folder_contents(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) {
      files[std::filesystem::relative(e.path(), dir).string()] = read_text(e.path());
    }
  }
  return files;
}

}  // namespace facectl::testing
