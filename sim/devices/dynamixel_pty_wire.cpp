#include "sim/devices/dynamixel_pty_wire.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "control/clock.hpp"
#include "drivers/protocol/dynamixel2_packet.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"

namespace facectl::sim {
namespace {

void write_all(int fd, const std::uint8_t* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EAGAIN || errno == EINTR) {
        pollfd p{fd, POLLOUT, 0};
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

}  // namespace

DynamixelPtyWire::DynamixelPtyWire(std::vector<std::unique_ptr<DynamixelServoSim>> servos)
    : servos_(std::move(servos)) {
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
  thread_ = std::thread([this] { run(); });
}

DynamixelPtyWire::~DynamixelPtyWire() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
}

std::uint64_t DynamixelPtyWire::requests_of(std::uint8_t instruction) const {
  return by_instruction_[instruction].load();
}

void DynamixelPtyWire::run() {
  std::vector<std::uint8_t> buf(8192);
  std::vector<std::uint8_t> params(8192);
  std::size_t len = 0;
  while (!stop_.load()) {
    pollfd p{master_, POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) continue;
    const ssize_t n = ::read(master_, buf.data() + len, buf.size() - len);
    if (n <= 0) {
      sleep_us(1000);
      continue;
    }
    len += static_cast<std::size_t>(n);
    for (;;) {
      dxl2::Packet pk;
      const dxl2::ParseResult r = dxl2::parse_packet({buf.data(), len}, pk, params);
      if (r == dxl2::ParseResult::kIncomplete && pk.consumed == 0) break;
      std::vector<std::uint8_t> raw(buf.begin(), buf.begin() + static_cast<long>(pk.consumed));
      std::memmove(buf.data(), buf.data() + pk.consumed, len - pk.consumed);
      len -= pk.consumed;
      if (r == dxl2::ParseResult::kIncomplete) break;
      // A bad CRC is dropped without a word, as a servo does.
      if (r != dxl2::ParseResult::kOk || pk.instruction == dxl2::kStatus) continue;
      requests_.fetch_add(1);
      by_instruction_[pk.instruction].fetch_add(1);
      serve(pk.id, pk.instruction, {params.begin(), params.begin() + pk.param_count}, raw.data(),
            raw.size());
    }
    if (len == buf.size()) len = 0;
  }
}

void DynamixelPtyWire::serve(std::uint8_t id, std::uint8_t instruction,
                             const std::vector<std::uint8_t>& params, const std::uint8_t* raw,
                             std::size_t raw_size) {
  if (faults_.echo.load()) write_all(master_, raw, raw_size);
  // Sync read: the servos answer in the order the request lists them.
  std::vector<std::uint8_t> order;
  if (instruction == dxl2::kSyncRead) {
    order.assign(params.begin() + std::min<std::size_t>(4, params.size()), params.end());
  } else {
    std::lock_guard lock(mutex_);
    for (auto& s : servos_) order.push_back(s->id());
  }
  for (const std::uint8_t target : order) {
    std::vector<std::uint8_t> reply;
    int delay_us = 0;
    {
      std::lock_guard lock(mutex_);
      for (auto& s : servos_) {
        if (s->id() != target) continue;
        s->handle(id, instruction, params, monotonic_ns(), reply);
        delay_us = 2 * s->byte(dxl_x::kReturnDelayTime);
      }
    }
    if (reply.empty() || faults_.mute_id.load() == target) continue;
    if (faults_.corrupt_next.load() > 0) {
      faults_.corrupt_next.fetch_sub(1);
      reply.back() ^= 0x5A;
    }
    sleep_us(delay_us + faults_.extra_delay_us.load());
    write_all(master_, reply.data(), reply.size());
  }
}

}  // namespace facectl::sim
