#include "firmware-host/config/live_link_face_config.hpp"

namespace facectl {

LiveLinkFaceOptions parse_live_link_face_config(const ConfigNode& node) {
  node.expect_keys({"bind", "port", "allow_remote", "allow", "takeover_ms"});
  LiveLinkFaceOptions o;
  parse_udp_listen_keys(node, o);
  if (auto n = node.get("takeover_ms")) o.takeover_s = n->number_in(0.0, 60'000.0) * 1e-3;
  return o;
}

}  // namespace facectl
