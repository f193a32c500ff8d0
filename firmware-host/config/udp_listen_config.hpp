#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/ipv4_cidr.hpp"
#include "firmware-host/config/udp_sender_rule.hpp"

namespace facectl {

// Where a live UDP input listens and whom it hears: the keys the runtime
// file's stream blocks (fap_stream:, live_link_face:) share.
struct UdpListenOptions {
  std::string bind_address = "127.0.0.1";  // beyond loopback only with allow_remote
  std::uint16_t port = 0;                  // 0: the system picks one
  bool allow_remote = false;
  // Senders heard; others are counted and dropped. Pin the port
  // (127.0.0.1:5005) to shut out the other processes on this host.
  std::vector<UdpSenderRule> allow = {{kIpv4Loopback, 0}};
};

// Reads `bind`, `port`, `allow_remote` and `allow` of `node` into `o` (the
// caller checks the block's keys). An address or sender beyond loopback
// without `allow_remote: true` is an error at its line.
void parse_udp_listen_keys(const ConfigNode& node, UdpListenOptions& o);

// The runtime file's `osc:` block (`facectl serve`'s OSC control): bind,
// port (default 9000), allow_remote and allow, nothing else.
UdpListenOptions parse_osc_config(const ConfigNode& node);

}  // namespace facectl
