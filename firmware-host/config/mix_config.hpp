#pragma once

#include <string>
#include <vector>

#include "firmware-host/config/config_node.hpp"

namespace facectl {

// The runtime file's `mix:` block: several inputs of `facectl run` at once,
// each group of face signals taking the first live source of its list
// (docs/INPUTS.md, "Several sources at once"). Signals are matched against
// the head's YAML keys only once the head is loaded (resolve_input_mix), so
// each pattern keeps where it was written for the error.
struct MixGroupConfig {
  std::string name;
  std::vector<std::string> signals;        // YAML keys or fnmatch(3) globs: jaw_*, eye*_deg
  std::vector<std::string> signals_where;  // "file:line:column: mix.groups.G.signals[i]"
  std::vector<std::string> sources;        // in priority order
};

struct MixConfig {
  std::vector<MixGroupConfig> groups;  // in file order
  std::vector<std::string> others;     // the sources of the signals no group names
  double stale_ms = 200.0;             // a source that sent nothing for this long gives way
  double fade_ms = 250.0;              // a group changing source crossfades over this
  double rate_hz = 0.0;                // the mix's rate; 0: the runtime's show_rate_hz
};

// The names `sources:` and `others:` take, as facectl run's options name them.
const std::vector<std::string>& mix_source_names();

// Parses a `mix:` block; ConfigError at the line of what is wrong (a key,
// an unknown source, a group without signals or sources).
MixConfig parse_mix_config(const ConfigNode& node);

}  // namespace facectl
