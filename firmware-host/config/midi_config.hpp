#pragma once

#include <string>
#include <vector>

#include "firmware-host/config/config_node.hpp"

namespace facectl {

// One control change to one face signal: value 0..127 maps linearly onto
// min..max, in the signal's YAML unit.
struct MidiControlRule {
  int channel = 1;  // 1..16, as MIDI devices label them
  int cc = 0;       // 0..119 (120..127 are channel mode messages)
  std::string signal;
  double min = 0.0;
  double max = 1.0;
  std::string where;  // "file:line:column: midi.controls[i]", for errors found later
};

// One note to one expression of the library: note on holds it at a weight
// of velocity / 127, note off lets it go.
struct MidiNoteRule {
  int channel = 1;
  int note = 60;  // 0..127; 60 is middle C
  std::string expression;
  std::string where;
};

// The runtime file's `midi:` block (`facectl run --midi`, docs/INPUTS.md,
// "MIDI"): facectl's ALSA sequencer client, whom it connects to at start,
// and the map from controls and notes to the face.
struct MidiConfig {
  std::string client = "facectl";    // the client name senders connect to
  std::vector<std::string> connect;  // ALSA addresses to subscribe to: "20:0", "nanoKONTROL2"
  double rate_hz = 100.0;            // how often a held pose is sent again to the tick
  std::vector<MidiControlRule> controls;
  std::vector<MidiNoteRule> notes;
};

// ConfigError at the line of what is wrong: a key, a channel, controller or
// note out of range, a note mapped twice or a signal twice to one control,
// a map with neither controls nor notes. One control may move several
// signals (both eyes).
MidiConfig parse_midi_config(const ConfigNode& node);

}  // namespace facectl
