#include "firmware-host/config/config_location.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace facectl {

namespace {

namespace fs = std::filesystem;

// `path` lies inside `dir` (both made absolute and normalised, symbolic links
// in their existing parts resolved).
bool inside(const fs::path& path, const fs::path& dir) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  if (ec) return false;
  const fs::path d = fs::weakly_canonical(dir, ec);
  if (ec || d.empty()) return false;
  const fs::path rel = p.lexically_relative(d);
  return !rel.empty() && *rel.begin() != "..";
}

}  // namespace

ShippedDirs choose_shipped_dirs(const std::string& exe, const ShippedDirChoice& choice) {
  std::error_code ec;
  if (!exe.empty() && inside(exe, choice.build_dir) && fs::is_directory(choice.source.config, ec)) {
    return choice.source;
  }
  return choice.installed;
}

ShippedDirs shipped_dirs() {
  // Compiled in for this file only (firmware-host/CMakeLists.txt), so a change
  // of install prefix rebuilds one file.
  static const ShippedDirs dirs = [] {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return choose_shipped_dirs(ec ? std::string() : exe.string(),
                               {FACECTL_BUILD_DIR,
                                {FACECTL_SOURCE_CONFIG_DIR, FACECTL_SOURCE_CONSOLE_DIR},
                                {FACECTL_INSTALL_CONFIG_DIR, FACECTL_INSTALL_CONSOLE_DIR}});
  }();
  return dirs;
}

std::string default_config_path() {
  if (const char* env = std::getenv("FACECTL_CONFIG")) return env;
  return shipped_dirs().config + "/facectl.yaml";
}

}  // namespace facectl
