#include "firmware-host/config/audio_config.hpp"

namespace facectl {

AudioConfig parse_audio_config(const ConfigNode& node) {
  node.expect_keys({"device", "lead_ms", "buffer_ms"});
  AudioConfig c;
  if (auto n = node.get("device")) {
    c.device = n->string();
    if (c.device.empty()) n->fail("an ALSA device name such as default or plughw:1,0");
  }
  if (auto n = node.get("lead_ms")) c.lead_s = n->number_in(0.0, 1000.0) * 1e-3;
  if (auto n = node.get("buffer_ms")) c.buffer_s = n->number_in(10.0, 1000.0) * 1e-3;
  return c;
}

}  // namespace facectl
