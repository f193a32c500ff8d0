#include "firmware-host/config/ipv4_cidr.hpp"

#include <arpa/inet.h>

#include <charconv>

namespace facectl {

std::optional<std::uint32_t> parse_ipv4_address(std::string_view text) {
  in_addr a{};
  if (inet_pton(AF_INET, std::string(text).c_str(), &a) != 1) return std::nullopt;
  return ntohl(a.s_addr);
}

std::optional<Ipv4Cidr> parse_ipv4_cidr(std::string_view text) {
  const auto slash = text.find('/');
  const auto address = parse_ipv4_address(text.substr(0, slash));
  if (!address) return std::nullopt;
  Ipv4Cidr c;
  if (slash != std::string_view::npos) {
    const std::string_view p = text.substr(slash + 1);
    const auto r = std::from_chars(p.data(), p.data() + p.size(), c.prefix);
    if (p.empty() || r.ec != std::errc() || r.ptr != p.data() + p.size() || c.prefix < 0 ||
        c.prefix > 32) {
      return std::nullopt;
    }
  }
  c.network = *address & c.mask();
  return c;
}

std::string ipv4_text(std::uint32_t address) {
  in_addr a{};
  a.s_addr = htonl(address);
  char buf[INET_ADDRSTRLEN] = "?";
  inet_ntop(AF_INET, &a, buf, sizeof buf);
  return buf;
}

std::string Ipv4Cidr::text() const {
  return ipv4_text(network) + "/" + std::to_string(prefix);
}

}  // namespace facectl
