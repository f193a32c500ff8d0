#include "firmware-host/config/fap_stream_config.hpp"

namespace facectl {

FapUdpOptions parse_fap_stream_config(const ConfigNode& node) {
  node.expect_keys(
      {"bind", "port", "allow_remote", "allow", "max_peers", "takeover_ms", "max_frame_jump"});
  FapUdpOptions o;
  parse_udp_listen_keys(node, o);
  if (auto n = node.get("max_peers")) o.max_peers = static_cast<std::size_t>(n->integer_in(2, 64));
  if (auto n = node.get("takeover_ms")) o.takeover_s = n->number_in(0.0, 60'000.0) * 1e-3;
  if (auto n = node.get("max_frame_jump")) o.limits.frame_jump = n->integer_in(1, 1'000'000);
  return o;
}

}  // namespace facectl
