#include "drivers/serial/serial_port.hpp"

// termios2 (BOTHER) from the kernel's headers: <termios.h> would redefine it.
#include <asm/termbits.h>
#include <fcntl.h>
#include <linux/serial.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "control/clock.hpp"

namespace facectl {
namespace {

std::runtime_error system_error(const std::string& device, const char* what) {
  return std::runtime_error(device + ": " + what + ": " + std::strerror(errno));
}

int poll_ms(std::int64_t ns) {
  if (ns <= 0) return 0;
  return static_cast<int>((ns + 999'999) / 1'000'000);
}

}  // namespace

SerialPort::SerialPort(const std::string& device, long baud) : device_(device), baud_(baud) {
  if (baud <= 0) throw std::runtime_error(device + ": baud " + std::to_string(baud) + " <= 0");
  fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw system_error(device, "cannot open");
  termios2 tio{};
  if (::ioctl(fd_, TCGETS2, &tio) != 0) {
    const auto e = system_error(device, "not a serial port (TCGETS2)");
    ::close(fd_);
    throw e;
  }
  // Raw 8N1, no flow control, no echo, no translation (cfmakeraw's flags).
  tio.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL |
                                        IXON | IXOFF | IXANY);
  tio.c_oflag &= ~static_cast<tcflag_t>(OPOST);
  tio.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
  tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS | CBAUD);
  tio.c_cflag |= CS8 | CREAD | CLOCAL | BOTHER;
  tio.c_ispeed = static_cast<speed_t>(baud);
  tio.c_ospeed = static_cast<speed_t>(baud);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::ioctl(fd_, TCSETS2, &tio) != 0) {
    const auto e = system_error(device, ("cannot set " + std::to_string(baud) + " baud").c_str());
    ::close(fd_);
    throw e;
  }
  // USB adapters (FTDI, as in the U2D2) hold received bytes up to their
  // latency timer, 16 ms by default: ask for low latency (1 ms). Ports that
  // are not such a device (a pty) say no, which is fine.
  serial_struct ss{};
  if (::ioctl(fd_, TIOCGSERIAL, &ss) == 0) {
    ss.flags |= ASYNC_LOW_LATENCY;
    ::ioctl(fd_, TIOCSSERIAL, &ss);
  }
  discard_input();
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

bool SerialPort::write_all(std::span<const std::uint8_t> bytes, std::int64_t timeout_ns) {
  const std::int64_t deadline = monotonic_ns() + timeout_ns;
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
    pollfd p{fd_, POLLOUT, 0};
    const std::int64_t left = deadline - monotonic_ns();
    if (left <= 0) {
      errno = ETIMEDOUT;
      return false;
    }
    if (::poll(&p, 1, poll_ms(left)) < 0 && errno != EINTR) return false;
  }
  return true;
}

long SerialPort::read_some(std::span<std::uint8_t> out, std::int64_t timeout_ns) {
  pollfd p{fd_, POLLIN, 0};
  int r = 0;
  do {
    r = ::poll(&p, 1, poll_ms(timeout_ns));
  } while (r < 0 && errno == EINTR);
  if (r < 0) return -1;
  if (r == 0) return 0;
  if ((p.revents & (POLLERR | POLLNVAL)) != 0) {
    errno = EIO;
    return -1;
  }
  const ssize_t n = ::read(fd_, out.data(), out.size());
  if (n < 0) return (errno == EAGAIN || errno == EINTR) ? 0 : -1;
  if (n == 0 && (p.revents & POLLHUP) != 0) {
    errno = EIO;  // the other end went away (an adapter unplugged, a pty closed)
    return -1;
  }
  return static_cast<long>(n);
}

void SerialPort::discard_input() {
  ::ioctl(fd_, TCFLSH, TCIFLUSH);
}

}  // namespace facectl
