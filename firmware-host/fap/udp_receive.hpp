#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

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

// One datagram into `buffer`, without blocking; nullopt when none is queued.
std::optional<UdpDatagram> receive_datagram(int fd, std::span<char> buffer);

}  // namespace facectl
