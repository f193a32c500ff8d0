#include "sim/devices/maestro_pty_wire.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "control/clock.hpp"

namespace facectl::sim {

MaestroPtyWire::MaestroPtyWire(MaestroSim maestro) : maestro_(std::move(maestro)) {
  static std::atomic<int> serial{0};
  link_ = "/tmp/facectl-maestro-" + std::to_string(::getpid()) + "-" +
          std::to_string(serial.fetch_add(1));
  open_pty();
  thread_ = std::thread([this] { run(); });
}

MaestroPtyWire::~MaestroPtyWire() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  close_pty();
}

void MaestroPtyWire::open_pty() {
  std::lock_guard lock(pty_mutex_);
  master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) {
    throw std::runtime_error(std::string("pty: ") + std::strerror(errno));
  }
  const std::string slave = ::ptsname(master_);
  slave_ = ::open(slave.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave_ < 0) throw std::runtime_error("pty " + slave + ": " + std::strerror(errno));
  termios t{};
  ::tcgetattr(slave_, &t);
  ::cfmakeraw(&t);  // no echo, no line editing, before the driver opens it
  ::tcsetattr(slave_, TCSANOW, &t);
  ::unlink(link_.c_str());
  if (::symlink(slave.c_str(), link_.c_str()) != 0) {
    throw std::runtime_error("symlink " + link_ + ": " + std::strerror(errno));
  }
}

void MaestroPtyWire::close_pty() {
  std::lock_guard lock(pty_mutex_);
  ::unlink(link_.c_str());
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
  slave_ = master_ = -1;
}

void MaestroPtyWire::unplug() {
  close_pty();
}

void MaestroPtyWire::replug() {
  {
    std::lock_guard lock(mutex_);
    maestro_.power_cycle();
  }
  open_pty();
}

void MaestroPtyWire::run() {
  std::uint8_t buf[512];
  std::vector<std::uint8_t> reply;
  while (!stop_.load()) {
    int fd = -1;
    {
      std::lock_guard lock(pty_mutex_);
      fd = master_;
    }
    if (fd < 0) {
      ::usleep(1000);
      continue;
    }
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, 5);
    std::lock_guard pty(pty_mutex_);
    if (master_ != fd) continue;  // unplugged meanwhile
    if (ready <= 0 || (p.revents & POLLIN) == 0) {
      std::lock_guard lock(mutex_);
      maestro_.advance(monotonic_ns());
      if ((p.revents & POLLHUP) != 0) ::usleep(1000);  // no one has the slave open
      continue;
    }
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) continue;
    bytes_.fetch_add(static_cast<std::uint64_t>(n));
    reply.clear();
    {
      std::lock_guard lock(mutex_);
      for (ssize_t i = 0; i < n; ++i) maestro_.feed(buf[i], monotonic_ns(), reply);
    }
    if (reply.empty() || faults_.mute.load()) continue;
    if (faults_.truncate_next.load() > 0) {
      faults_.truncate_next.fetch_sub(1);
      reply.pop_back();
    }
    std::size_t done = 0;
    while (done < reply.size()) {
      const ssize_t w = ::write(fd, reply.data() + done, reply.size() - done);
      if (w > 0) {
        done += static_cast<std::size_t>(w);
      } else if (errno == EAGAIN || errno == EINTR) {
        pollfd o{fd, POLLOUT, 0};
        ::poll(&o, 1, 10);
      } else {
        break;
      }
    }
  }
}

}  // namespace facectl::sim
