#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "firmware-host/config/ipv4_cidr.hpp"

namespace facectl {

// One entry of a UDP stream's allow list: an IPv4 address or network and,
// optionally, the one source port its sender uses ("127.0.0.1:5005",
// "10.0.0.0/24:5005"). On a shared host the address says nothing (every
// local process sends from 127.0.0.1); the port is what pins the sender.
struct UdpSenderRule {
  Ipv4Cidr network;
  std::uint16_t port = 0;  // 0: any port (no UDP sender sends from port 0)

  bool admits(std::uint32_t address, std::uint16_t from_port) const {
    return network.contains(address) && (port == 0 || port == from_port);
  }
  std::string text() const;
  bool operator==(const UdpSenderRule&) const = default;
};

// "a.b.c.d", "a.b.c.d/prefix", either with ":port" (1..65535); nullopt when
// it is none of these.
std::optional<UdpSenderRule> parse_udp_sender_rule(std::string_view text);

}  // namespace facectl
