#pragma once

#include <string>

#include "firmware-host/config/config_node.hpp"

namespace facectl {

// The runtime file's `audio:` block: where `facectl run --audio FILE` plays
// the sound its input or show is timed to (docs/INPUTS.md, "Audio").
struct AudioConfig {
  std::string device = "default";  // an ALSA PCM name: default, plughw:1,0, hw:Loopback,0,0
  // The face plays this far ahead of the sound: what the shaping and the
  // actuators take to move (the default rig's jaw strut: about 70 ms to half
  // a step, docs/PERFORMANCE.md).
  double lead_s = 0.07;
  double buffer_s = 0.1;  // ALSA's buffer: more rides out a busy machine, and delays the start
};

// ConfigError at the line of an unknown key, an empty device, a lead outside
// 0..1000 ms or a buffer outside 10..1000 ms.
AudioConfig parse_audio_config(const ConfigNode& node);

}  // namespace facectl
