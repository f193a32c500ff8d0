#pragma once

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace facectl::testing {

// A file with the given text that lives as long as this object.
class TempFile {
 public:
  explicit TempFile(const std::string& text, const std::string& suffix = ".yaml") {
    std::string templ = "/tmp/facectl-test-XXXXXX" + suffix;
    const int fd = mkstemps(templ.data(), static_cast<int>(suffix.size()));
    if (fd >= 0) close(fd);
    path_ = templ;
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::remove(path_.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace facectl::testing
