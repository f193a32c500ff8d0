// One datagram of the Live Link Face stream (docs/INPUTS.md): the packet
// parser must read it or refuse it with LiveLinkFacePacketError, and what
// it reads must be what the stream plays (finite values, bounded names).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "firmware-host/inputs/live_link_face_packet.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto p = facectl::parse_live_link_face_packet(std::span(data, size));
    if (p.device_id.size() > facectl::kLiveLinkFaceMaxName ||
        p.subject.size() > facectl::kLiveLinkFaceMaxName) {
      std::abort();
    }
    for (float v : p.values) {
      if (!std::isfinite(v)) std::abort();
    }
  } catch (const facectl::LiveLinkFacePacketError&) {
  }
  return 0;
}
