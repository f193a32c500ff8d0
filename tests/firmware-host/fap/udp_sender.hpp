// A UDP sender on loopback for the FAP stream's tests, and a wait for the
// stream's counters.
#pragma once

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <functional>
#include <string>

#include "firmware-host/fap/fap_udp_stream.hpp"

namespace facectl::testing {

class Sender {
 public:
  // To 127.0.0.1:`port`, from `from` (any address of 127.0.0.0/8) and a port
  // of its own.
  explicit Sender(std::uint16_t port, const char* from = "127.0.0.1")
      : fd_(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {
    sockaddr_in self{};
    self.sin_family = AF_INET;
    inet_pton(AF_INET, from, &self.sin_addr);
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&self), sizeof self), 0) << from;
    to_.sin_family = AF_INET;
    aim(port);
    inet_pton(AF_INET, "127.0.0.1", &to_.sin_addr);
  }
  ~Sender() { ::close(fd_); }
  Sender(const Sender&) = delete;
  Sender& operator=(const Sender&) = delete;

  void send(const std::string& text) {
    ASSERT_EQ(
        ::sendto(fd_, text.data(), text.size(), 0, reinterpret_cast<sockaddr*>(&to_), sizeof to_),
        static_cast<ssize_t>(text.size()));
  }
  // Sends to another port from now on (a sender made before the stream, so
  // that the stream's allow list can pin its port).
  void aim(std::uint16_t port) { to_.sin_port = htons(port); }
  // The port it sends from.
  std::uint16_t own_port() const { return ntohs(self().sin_port); }
  // "address:port" as the stream names this sender.
  std::string name() const {
    const sockaddr_in me = self();
    char ip[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &me.sin_addr, ip, sizeof ip);
    return std::string(ip) + ":" + std::to_string(ntohs(me.sin_port));
  }

 private:
  sockaddr_in self() const {
    sockaddr_in me{};
    socklen_t len = sizeof me;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&me), &len);
    return me;
  }

  int fd_;
  sockaddr_in to_{};
};

// Polls until `done(stats)` holds, for up to about 2 s.
inline void poll_until(FapUdpStream& s, const std::function<bool(const FapUdpStats&)>& done) {
  for (int i = 0; i < 200; ++i) {
    s.wait_and_poll(10);
    if (done(s.stats())) return;
  }
}

// Polls until `frames` frames and `malformed` rejections have been counted.
inline void poll_until(FapUdpStream& s, std::uint64_t frames, std::uint64_t malformed) {
  poll_until(
      s, [&](const FapUdpStats& st) { return st.frames >= frames && st.malformed >= malformed; });
}

// Polls until `datagrams` datagrams have been received.
inline void poll_until_datagrams(FapUdpStream& s, std::uint64_t datagrams) {
  poll_until(s, [&](const FapUdpStats& st) { return st.datagrams >= datagrams; });
}

}  // namespace facectl::testing
