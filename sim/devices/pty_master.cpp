#include "sim/devices/pty_master.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <stdexcept>

namespace facectl::sim {

PtyMaster::PtyMaster() {
  master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) {
    throw std::runtime_error(std::string("pty: ") + std::strerror(errno));
  }
  device_ = ::ptsname(master_);
  slave_ = ::open(device_.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave_ < 0) throw std::runtime_error("pty " + device_ + ": " + std::strerror(errno));
  termios t{};
  ::tcgetattr(slave_, &t);
  ::cfmakeraw(&t);  // no echo, no line editing, before the driver opens it
  ::tcsetattr(slave_, TCSANOW, &t);
}

PtyMaster::~PtyMaster() {
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
}

std::size_t PtyMaster::read(std::uint8_t* out, std::size_t size, int timeout_ms) {
  pollfd p{master_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) <= 0) return 0;
  const ssize_t n = ::read(master_, out, size);
  if (n <= 0) {
    sleep_us(1000);
    return 0;
  }
  return static_cast<std::size_t>(n);
}

void PtyMaster::write_all(const std::uint8_t* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(master_, data, n);
    if (w < 0) {
      if (errno == EAGAIN || errno == EINTR) {
        pollfd p{master_, POLLOUT, 0};
        ::poll(&p, 1, 10);
        continue;
      }
      return;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
}

void sleep_us(int us) {
  if (us <= 0) return;
  timespec t{us / 1'000'000, (us % 1'000'000) * 1000L};
  nanosleep(&t, nullptr);
}

}  // namespace facectl::sim
