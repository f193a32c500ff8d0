#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "firmware-host/config/udp_listen_config.hpp"

namespace facectl {

// Asks the kernel to stamp each datagram with the socket's count of
// datagrams dropped so far for want of receive-buffer room (SO_RXQ_OVFL).
// Returns false when it refuses.
bool enable_kernel_drop_count(int fd);

struct UdpDatagram {
  std::size_t size = 0;
  std::uint32_t address = 0;  // sender, host byte order
  std::uint16_t port = 0;
  std::optional<std::uint32_t> kernel_drops;  // SO_RXQ_OVFL's running count (wraps at 2^32)
};

// A non-blocking UDP socket bound where `o` says, counting kernel drops.
struct BoundUdpSocket {
  int fd = -1;
  std::uint16_t port = 0;  // the one bound (the system's pick for port 0)
  std::string bound;       // "address:port"
};

// Throws ConfigError naming the stream (`what`, "FAP stream") and its
// address when it cannot bind, or when the address is beyond loopback
// without allow_remote (`block`.allow_remote, the runtime file's key);
// warns on stderr when it binds beyond loopback. The caller closes the fd.
BoundUdpSocket bind_udp_socket(const UdpListenOptions& o, const std::string& what,
                               const std::string& block);

// One datagram into `buffer`, without blocking; nullopt when none is queued.
std::optional<UdpDatagram> receive_datagram(int fd, std::span<char> buffer);

}  // namespace facectl
