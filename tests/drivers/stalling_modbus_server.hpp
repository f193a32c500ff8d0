// A hostile Modbus TCP peer on 127.0.0.1: it answers every request with the
// first 4 bytes of a reply (the transaction and protocol ids) and then says
// nothing more, keeping the connection open. A client that has not set its
// byte timeout waits libmodbus's 500 ms on each such reply.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <thread>

namespace facectl::testing {

class StallingModbusServer {
 public:
  StallingModbusServer() {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
    ::listen(listen_fd_, 4);
    socklen_t len = sizeof addr;
    ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~StallingModbusServer() {
    stop_.store(true);
    thread_.join();
    ::close(listen_fd_);
  }
  StallingModbusServer(const StallingModbusServer&) = delete;
  StallingModbusServer& operator=(const StallingModbusServer&) = delete;

  int port() const { return port_; }
  int requests() const { return requests_.load(); }

 private:
  void serve() {
    int conn = -1;
    while (!stop_.load()) {
      pollfd p[2] = {{listen_fd_, POLLIN, 0}, {conn, POLLIN, 0}};  // poll skips fd -1
      if (::poll(p, 2, 20) <= 0) continue;
      if ((p[0].revents & POLLIN) != 0) {
        if (conn >= 0) ::close(conn);
        conn = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        continue;
      }
      unsigned char request[260];
      const ssize_t n = ::recv(conn, request, sizeof request, 0);
      if (n <= 0) {
        ::close(conn);
        conn = -1;
        continue;
      }
      ++requests_;
      const unsigned char partial[4] = {request[0],
                                        n > 1 ? request[1] : static_cast<unsigned char>(0), 0, 0};
      ::send(conn, partial, sizeof partial, MSG_NOSIGNAL);
    }
    if (conn >= 0) ::close(conn);
  }

  int listen_fd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<int> requests_{0};
  std::thread thread_;
};

}  // namespace facectl::testing
