#include "facectl/face/bounded_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

// Closes the descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_bounded_file(const std::string& path, std::uintmax_t max_bytes,
                              const std::string& what) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (f.fd < 0) {
    throw InputError(path + ": cannot open file (" + std::strerror(errno) +
                     "; expected a readable " + what + ")");
  }
  // The type of what was opened, not of what the name pointed to earlier.
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) {
    throw InputError(path + ": cannot read file (" + std::strerror(errno) + ")");
  }
  if (S_ISDIR(st.st_mode)) throw InputError(path + ": is a directory, expected a " + what);
  if (!S_ISREG(st.st_mode)) throw InputError(path + ": is not a regular file, expected a " + what);
  const auto too_big = [&](std::uintmax_t size) {
    return InputError(path + ": file is " + std::to_string(size) + " bytes, expected at most " +
                      std::to_string(max_bytes) + " for a " + what);
  };
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    throw too_big(static_cast<std::uintmax_t>(st.st_size));
  }
  // Read to the end, never past max_bytes + 1: a size that changed since fstat
  // (a growing file, /proc) is bounded all the same.
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(path + ": cannot read file (" + std::strerror(errno) + ")");
    }
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) throw too_big(text.size());
  }
  return text;
}

}  // namespace facectl::face
