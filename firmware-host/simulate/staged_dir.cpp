#include "firmware-host/simulate/staged_dir.hpp"

#include <stdexcept>
#include <string>

namespace facectl {

namespace fs = std::filesystem;

StagedDir::StagedDir(const fs::path& target) : target_(fs::absolute(target).lexically_normal()) {
  if (!target_.has_filename()) target_ = target_.parent_path();
  staging_ = target_.parent_path() / ("." + target_.filename().string() + ".partial");
  fs::remove_all(staging_);
  fs::create_directories(staging_);
}

StagedDir::~StagedDir() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void StagedDir::commit() {
  // The earlier output is moved aside, not deleted, until the new one is in
  // place: if that fails, it is put back, and no data is lost either way. A
  // run that died between the two renames left only ".DIR.previous": that is
  // the earlier output, so it is put back first.
  const fs::path previous =
      target_.parent_path() / ("." + target_.filename().string() + ".previous");
  if (!fs::exists(fs::symlink_status(target_)) && fs::exists(fs::symlink_status(previous))) {
    fs::rename(previous, target_);
  }
  fs::remove_all(previous);  // superseded: a run died after both renames
  const bool had = fs::exists(fs::symlink_status(target_));
  if (had) fs::rename(target_, previous);
  try {
    fs::rename(staging_, target_);
  } catch (const fs::filesystem_error& e) {
    std::error_code restore;
    if (had) fs::rename(previous, target_, restore);
    if (restore) {
      throw std::runtime_error(std::string(e.what()) + "; the earlier output is kept in " +
                               previous.string());
    }
    throw;
  }
  committed_ = true;
  std::error_code ignored;
  fs::remove_all(previous, ignored);
}

}  // namespace facectl
