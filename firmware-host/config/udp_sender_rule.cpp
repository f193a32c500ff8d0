#include "firmware-host/config/udp_sender_rule.hpp"

#include <charconv>

namespace facectl {

std::optional<UdpSenderRule> parse_udp_sender_rule(std::string_view text) {
  const auto colon = text.find(':');
  const auto network = parse_ipv4_cidr(text.substr(0, colon));
  if (!network) return std::nullopt;
  UdpSenderRule rule{*network, 0};
  if (colon != std::string_view::npos) {
    const std::string_view p = text.substr(colon + 1);
    unsigned port = 0;
    const auto r = std::from_chars(p.data(), p.data() + p.size(), port);
    if (p.empty() || r.ec != std::errc() || r.ptr != p.data() + p.size() || port < 1 ||
        port > 65535) {
      return std::nullopt;
    }
    rule.port = static_cast<std::uint16_t>(port);
  }
  return rule;
}

std::string UdpSenderRule::text() const {
  return network.text() + (port == 0 ? "" : ":" + std::to_string(port));
}

}  // namespace facectl
