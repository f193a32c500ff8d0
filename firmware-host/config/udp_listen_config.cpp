#include "firmware-host/config/udp_listen_config.hpp"

namespace facectl {

void parse_udp_listen_keys(const ConfigNode& node, UdpListenOptions& o) {
  if (auto n = node.get("allow_remote")) o.allow_remote = n->boolean();
  const char* remote_hint = ", or allow_remote: true to go beyond loopback";
  if (auto n = node.get("bind")) {
    o.bind_address = n->string();
    const auto address = parse_ipv4_address(o.bind_address);
    if (!address) n->fail("an IPv4 address to bind to");
    if (!kIpv4Loopback.contains(*address) && !o.allow_remote) {
      n->fail(std::string("a loopback address (127.0.0.0/8)") + remote_hint);
    }
  }
  if (auto n = node.get("port")) o.port = static_cast<std::uint16_t>(n->integer_in(0, 65535));
  if (auto n = node.get("allow")) {
    o.allow.clear();
    for (const ConfigNode& item : n->items()) {
      const auto rule = parse_udp_sender_rule(item.string());
      if (!rule) {
        item.fail(
            "an IPv4 address or network, optionally with a port (a.b.c.d, a.b.c.d/prefix, "
            "a.b.c.d:port or a.b.c.d/prefix:port)");
      }
      if (!rule->network.within(kIpv4Loopback) && !o.allow_remote) {
        item.fail(std::string("senders within loopback (127.0.0.0/8)") + remote_hint);
      }
      o.allow.push_back(*rule);
    }
    if (o.allow.empty()) n->fail("at least one address or network");
  }
}

UdpListenOptions parse_osc_config(const ConfigNode& node) {
  node.expect_keys({"bind", "port", "allow_remote", "allow"});
  UdpListenOptions o;
  o.port = 9000;
  parse_udp_listen_keys(node, o);
  return o;
}

}  // namespace facectl
