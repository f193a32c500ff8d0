#include "firmware-host/simulate/staged_dir.hpp"

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
  fs::remove_all(target_);
  fs::rename(staging_, target_);
  committed_ = true;
}

}  // namespace facectl
