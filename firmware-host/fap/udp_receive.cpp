#include "firmware-host/fap/udp_receive.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <cstring>

namespace facectl {

bool enable_kernel_drop_count(int fd) {
  const int on = 1;
  return ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) == 0;
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
