#pragma once

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/udp_listen_config.hpp"

namespace facectl {

// The Live Link Face stream (`facectl run --live-link-face`): where it
// listens, whom it hears, and when another phone may take over.
struct LiveLinkFaceOptions : UdpListenOptions {
  LiveLinkFaceOptions() { port = 11111; }  // the app's default target port
  double takeover_s = 0.5;                 // the playing sender silent this long: another may play
};

// The runtime file's `live_link_face:` block: bind, port, allow_remote,
// allow (as fap_stream:) and takeover_ms.
LiveLinkFaceOptions parse_live_link_face_config(const ConfigNode& node);

}  // namespace facectl
