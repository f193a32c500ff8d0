#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/udp_listen_config.hpp"

namespace facectl {

// Upper bounds on every field of a FAP datagram (docs/FAP.md, "Live stream
// over UDP"). A datagram past any of them is counted and never played, and
// nothing of it is kept, so it cannot lock out a sender.
struct FapUdpLimits {
  std::size_t name_length = 64;    // header name, characters
  double min_frame_rate = 1.0;     // header frame rate, frames per second
  double max_frame_rate = 1000.0;  //
  long frame_count = 100'000'000;  // header frame count (a day at 1000 fps)
  // A frame's number may be at most this far above the sender's previous one
  // (40 s at 25 fps), plus the frames of the time since that one was accepted
  // (a sender that numbers by time skips what it did not send); the first
  // frame after a header at most this.
  long frame_jump = 1000;
  std::size_t frames_per_datagram = 64;
  double value = 100'000.0;  // |FAP value| in FAPU; the face envelope clamps far below it
};

// The live FAP stream: where it listens, whom it hears and its bounds.
struct FapUdpOptions : UdpListenOptions {
  // Senders with state at once, at least 2: a new one takes the slot of the
  // one heard least recently other than the one playing.
  std::size_t max_peers = 8;
  double takeover_s = 0.5;  // the playing sender silent this long: another may play
  FapUdpLimits limits;
};

// The runtime file's `fap_stream:` block. A bind address or an allowed
// sender beyond loopback without `allow_remote: true` is an error at its line.
FapUdpOptions parse_fap_stream_config(const ConfigNode& node);

}  // namespace facectl
