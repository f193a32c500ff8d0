#pragma once

#include <optional>
#include <string>

#include "control/command/command_shaper.hpp"
#include "control/safety/safety_state_machine.hpp"
#include "firmware-host/config/audio_config.hpp"
#include "firmware-host/config/fap_stream_config.hpp"
#include "firmware-host/config/hardware_config.hpp"
#include "firmware-host/config/live_link_face_config.hpp"
#include "firmware-host/config/midi_config.hpp"
#include "firmware-host/config/mix_config.hpp"
#include "firmware-host/config/serve_config.hpp"

namespace facectl {

struct RealtimeSettings {
  int priority = 80;        // SCHED_FIFO priority; 0 = do not ask for SCHED_FIFO
  int cpu = -1;             // pin the loop to this CPU; -1 = no affinity
  bool lock_memory = true;  // mlockall(MCL_CURRENT | MCL_FUTURE)
  // Request for /dev/cpu_dma_latency while running, in µs; -1 = leave alone.
  // 0 keeps idle CPUs out of deep sleep states (what cyclictest does), which
  // cuts wake-up latency from milliseconds to tens of µs on virtual machines.
  int cpu_dma_latency_us = 0;
};

// config/facectl.yaml: the runtime settings and which head, rig, expression
// library and show to use (paths relative to this file).
struct RuntimeConfig {
  std::string file;
  double rate_hz = 1000.0;
  RealtimeSettings realtime;
  SafetyParams safety;
  ShapingParams shaping;
  std::size_t telemetry_ring = 16384;  // records; 16 s at 1 kHz
  double show_rate_hz = 250.0;
  std::string head_path;
  std::string rig_path;
  std::string expressions_path;
  std::string show_path;
  std::string visemes_path;   // `visemes:`, default fap/visemes.yaml beside this file
  std::string retarget_path;  // `retarget:`, default retarget.yaml beside the head file
  HardwareMode hardware = HardwareMode::kSim;  // `hardware:`; `facectl run --hardware` overrides
  std::optional<SafetyIoConfig> safety_io;     // required by hardware: real
  std::optional<GamepadConfig> gamepad;        // puppeteering (`facectl run --gamepad`)
  ServeConfig serve;                           // `facectl serve`
  std::optional<FapUdpOptions> fap_stream;     // the live FAP stream (run --fap-stream)
  std::optional<LiveLinkFaceOptions> live_link_face;  // run --live-link-face
  std::optional<UdpListenOptions> osc;                // `facectl serve`'s OSC control
  std::optional<MidiConfig> midi;                     // run --midi (ALSA sequencer)
  std::optional<MixConfig> mix;                       // several inputs of `facectl run` at once
  AudioConfig audio;                                  // run --audio (ALSA playback)
};

RuntimeConfig load_runtime_config(const std::string& path);

}  // namespace facectl
