#pragma once

#include <optional>
#include <string>
#include <vector>

namespace facectl {

struct RunOptions {
  std::string config;                // runtime file; empty = the shipped default
  std::optional<std::string> show;   // overrides the runtime file's show
  std::optional<double> duration_s;  // run this long (the show loops); else play the show once
  std::optional<double> rate_hz;
  std::optional<std::string> record;    // telemetry CSV path
  std::optional<std::string> hardware;  // "sim" or "real": overrides the runtime file
  std::optional<std::string> input;     // play this input file instead of the show (docs/INPUTS.md)
  std::optional<std::string> format;    // the input's format; else detected from its content
  bool fap_stream = false;           // play the runtime file's fap_stream (UDP) instead of a show
  bool live_link_face = false;       // play the runtime file's live_link_face stream (UDP)
  bool gamepad = false;              // puppeteer from the runtime file's gamepad, not a show
  bool midi = false;                 // play the runtime file's midi map (ALSA sequencer)
  std::optional<std::string> audio;  // play this sound, the input (or show) timed by it
  // With gamepad, input or a stream: write what was played as a show.
  std::optional<std::string> record_show;
  std::vector<std::string> inject;  // fault rehearsal on simulated hardware
  bool quiet = false;               // no status line even on a terminal
};

// Exit codes: 0 success; 1 a check failed (a limit breach or lost telemetry);
// 2 unusable input, or real hardware that cannot be opened; 3 the run ended in
// FAULT or ESTOP.
int run_command(const RunOptions& options);

}  // namespace facectl
