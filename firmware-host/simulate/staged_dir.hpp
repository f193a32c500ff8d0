#pragma once

#include <filesystem>

namespace facectl {

// An output folder written all at once: files go into a hidden sibling
// (".<name>.partial") that replaces the target only by commit(). Destroyed
// without commit(), it removes the sibling and leaves the target as it was.
class StagedDir {
 public:
  explicit StagedDir(const std::filesystem::path& target);
  ~StagedDir();
  StagedDir(const StagedDir&) = delete;
  StagedDir& operator=(const StagedDir&) = delete;

  const std::filesystem::path& path() const { return staging_; }
  // Replaces the target by the staged folder. An existing target is moved to
  // ".<name>.previous" first and removed only once the new one is in place;
  // if that rename fails, the old target is restored and the error thrown.
  void commit();

 private:
  std::filesystem::path target_, staging_;
  bool committed_ = false;
};

}  // namespace facectl
