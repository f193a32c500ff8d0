#include "firmware-host/fap/udp_receive.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace facectl {

bool enable_kernel_drop_count(int fd) {
  const int on = 1;
  return ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) == 0;
}

BoundUdpSocket bind_udp_socket(const UdpListenOptions& o, const std::string& what,
                               const std::string& block) {
  const std::string where = what + " " + o.bind_address + ":" + std::to_string(o.port);
  const auto address = parse_ipv4_address(o.bind_address);
  if (!address) {
    throw ConfigError(where + ": expected an IPv4 address to bind to, found '" + o.bind_address +
                      "'");
  }
  if (!kIpv4Loopback.contains(*address) && !o.allow_remote) {
    throw ConfigError(where +
                      ": expected a loopback address (127.0.0.0/8), found one beyond loopback: "
                      "binding it needs allow_remote (" +
                      block + ".allow_remote: true)");
  }
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(o.port);
  addr.sin_addr.s_addr = htonl(*address);
  BoundUdpSocket s;
  s.fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (s.fd < 0) throw ConfigError(where + ": socket: " + std::strerror(errno));
  if (!enable_kernel_drop_count(s.fd) ||
      ::bind(s.fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const std::string err = std::strerror(errno);
    ::close(s.fd);
    throw ConfigError(where + ": cannot bind: " + err);
  }
  socklen_t len = sizeof addr;
  ::getsockname(s.fd, reinterpret_cast<sockaddr*>(&addr), &len);
  s.port = ntohs(addr.sin_port);
  s.bound = o.bind_address + ":" + std::to_string(s.port);
  if (!kIpv4Loopback.contains(*address)) {
    std::fprintf(stderr,
                 "facectl: warning: %s %s listens beyond loopback: its datagrams are not "
                 "authenticated, only the allow list (%s.allow) keeps others out\n",
                 what.c_str(), s.bound.c_str(), block.c_str());
  }
  return s;
}

std::optional<UdpDatagram> receive_datagram(int fd, std::span<char> buffer) {
  sockaddr_in peer{};
  iovec iov{buffer.data(), buffer.size()};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(std::uint32_t))];
  msghdr msg{};
  msg.msg_name = &peer;
  msg.msg_namelen = sizeof peer;
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof control;
  const ssize_t n = ::recvmsg(fd, &msg, MSG_DONTWAIT);
  if (n < 0) return std::nullopt;  // EAGAIN: nothing queued (other errors: next time)
  UdpDatagram d;
  d.size = static_cast<std::size_t>(n);
  d.address = ntohl(peer.sin_addr.s_addr);
  d.port = ntohs(peer.sin_port);
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
      std::uint32_t drops = 0;
      std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
      d.kernel_drops = drops;
    }
  }
  return d;
}

}  // namespace facectl
