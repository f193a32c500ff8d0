#include "firmware-host/fap/udp_listener.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>

namespace facectl {

UdpListener::UdpListener(const UdpListenOptions& options, const std::string& what,
                         const std::string& block, std::size_t max_datagram, Handler handler)
    : allow_(options.allow),
      buffer_(max_datagram + 1),
      socket_(bind_udp_socket(options, what, block)),
      handler_(std::move(handler)) {}

UdpListener::~UdpListener() {
  stop();
  ::close(socket_.fd);
}

bool UdpListener::allowed(const UdpDatagram& d) const {
  return std::any_of(allow_.begin(), allow_.end(),
                     [&](const UdpSenderRule& r) { return r.admits(d.address, d.port); });
}

std::uint64_t UdpListener::new_kernel_drops(const UdpDatagram& d) {
  if (!d.kernel_drops) return 0;
  // A running count since the socket opened, 32 bits wide: what it grew.
  const std::uint32_t grew = *d.kernel_drops - last_drop_count_;
  last_drop_count_ = *d.kernel_drops;
  return grew;
}

std::size_t UdpListener::poll() {
  // The buffer and the handler's state belong to the receiving thread alone.
  if (receiving_.load() && receiver_.load() != std::this_thread::get_id()) {
    throw std::logic_error("UdpListener::poll: a receiver thread is running (start())");
  }
  std::size_t played = 0;
  while (const auto d = receive_datagram(socket_.fd, buffer_)) {
    played += handler_(*d, std::string_view(buffer_.data(), d->size));
  }
  return played;
}

std::size_t UdpListener::wait_and_poll(int timeout_ms) {
  pollfd p{socket_.fd, POLLIN, 0};
  ::poll(&p, 1, timeout_ms);
  return poll();
}

void UdpListener::start() {
  if (running_.exchange(true)) return;
  receiving_.store(true);
  thread_ = std::thread([this] {
    receiver_.store(std::this_thread::get_id());
    while (running_.load(std::memory_order_relaxed)) wait_and_poll(20);
  });
}

void UdpListener::stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
  // Only now: until the join the receiver may still be in the handler; and a
  // later thread may be given the old one's id.
  receiver_.store({});
  receiving_.store(false);
}

}  // namespace facectl
