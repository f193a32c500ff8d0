#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "firmware-host/config/udp_listen_config.hpp"
#include "firmware-host/fap/udp_receive.hpp"

namespace facectl {

// What the live UDP inputs share (the FAP stream, the Live Link Face
// stream): the bound socket, the allow list, the kernel's drop count, and
// reading either by polling from one thread or on a thread of its own.
// Each datagram goes to the handler, which returns the frames it played.
class UdpListener {
 public:
  using Handler = std::function<std::size_t(const UdpDatagram&, std::string_view)>;

  // Binds as bind_udp_socket (`what` and `block` name the stream in errors);
  // datagrams longer than max_datagram reach the handler cut to
  // max_datagram + 1 bytes (so that the handler can tell).
  UdpListener(const UdpListenOptions& options, const std::string& what, const std::string& block,
              std::size_t max_datagram, Handler handler);
  ~UdpListener();
  UdpListener(const UdpListener&) = delete;
  UdpListener& operator=(const UdpListener&) = delete;

  std::uint16_t port() const { return socket_.port; }
  int fd() const { return socket_.fd; }
  const std::string& bound() const { return socket_.bound; }

  // Whether an allow-list entry admits the datagram's sender.
  bool allowed(const UdpDatagram& d) const;
  // The datagrams the kernel dropped since the last datagram counted (from
  // the handler: SO_RXQ_OVFL's running count, 32 bits wide).
  std::uint64_t new_kernel_drops(const UdpDatagram& d);

  // Handles every datagram already queued, without blocking; returns the
  // frames played. From one thread at a time: while start()'s thread runs,
  // only from it (else std::logic_error).
  std::size_t poll();
  // Waits up to timeout_ms for a datagram, then poll()s.
  std::size_t wait_and_poll(int timeout_ms);
  // A thread that wait_and_poll()s until stop() (or destruction).
  void start();
  void stop();

 private:
  const std::vector<UdpSenderRule> allow_;
  // Before the socket: nothing would close its fd if this threw after it.
  std::vector<char> buffer_;  // the receiving thread's
  const BoundUdpSocket socket_;
  const Handler handler_;
  std::uint32_t last_drop_count_ = 0;  // SO_RXQ_OVFL's last running count
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> receiving_{false};       // from start() until stop() has joined
  std::atomic<std::thread::id> receiver_{};  // start()'s thread, once it runs
};

}  // namespace facectl
