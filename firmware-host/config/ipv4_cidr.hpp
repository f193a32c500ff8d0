#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace facectl {

// An IPv4 network, "a.b.c.d/prefix" (a bare address is a /32). Addresses are
// in host byte order.
struct Ipv4Cidr {
  std::uint32_t network = 0;  // host bits cleared
  int prefix = 32;            // 0..32

  std::uint32_t mask() const { return prefix == 0 ? 0 : ~std::uint32_t{0} << (32 - prefix); }
  bool contains(std::uint32_t address) const { return (address & mask()) == network; }
  // True when every address of this network is within `other`.
  bool within(const Ipv4Cidr& other) const {
    return prefix >= other.prefix && other.contains(network);
  }
  std::string text() const;
  bool operator==(const Ipv4Cidr&) const = default;
};

// Loopback, 127.0.0.0/8.
inline constexpr Ipv4Cidr kIpv4Loopback{0x7F000000u, 8};

// A dotted quad with an optional "/prefix"; nullopt when it is not one.
std::optional<Ipv4Cidr> parse_ipv4_cidr(std::string_view text);
// A dotted quad alone, in host byte order.
std::optional<std::uint32_t> parse_ipv4_address(std::string_view text);
std::string ipv4_text(std::uint32_t address);

}  // namespace facectl
