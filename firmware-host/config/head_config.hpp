#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "control/command/face_layout.hpp"
#include "control/envelope/mandible_envelope.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// An envelope as a head or rig file states it, with where it was stated.
// Axes the block does not state are absent, so they neither narrow nor widen.
struct EnvelopeSpec {
  std::optional<Range> pitch;
  std::optional<Range> yaw;
  std::optional<Range> protrusion;
  bool widen_override = false;
  std::string where;  // file:line:column of the block
};

// Two muscles that pull one feature in opposite directions. Driven together
// they fight (a lip corner pulled up and down at once tears skin or stalls a
// servo); `facectl verify` proves the rig keeps c_a + c_b <= max_sum.
struct AntagonistPair {
  std::size_t a = 0, b = 0;  // face signal indices
  double max_sum = 1.0;
  std::string where;
};

struct HeadConfig {
  std::string file;
  std::string name;
  std::vector<std::string> muscles;
  // The FACS action units each muscle serves (head.yaml `facs`), by muscle
  // index; checked against the retargeting table (inputs/retarget_table.hpp).
  std::vector<std::vector<int>> muscle_facs;
  std::vector<std::string> muscle_where;  // file:line:column of each muscle's entry
  std::vector<std::string> passive_muscles;
  std::map<std::string, Range> rigid_ranges;  // SI, keyed by rigid signal name
  std::optional<EnvelopeSpec> envelope;
  std::vector<AntagonistPair> antagonists;
  FaceLayout layout{{}};
  std::array<double, kMaxFaceSignals> neutral{};  // SI, full pose
  std::string neutral_where;  // file:line:column of `neutral:`, or of `head:` without one
};

HeadConfig load_head_config(const std::string& path);

// Parses a `mandible_envelope:` block (head or rig).
EnvelopeSpec parse_envelope(const ConfigNode& node);

}  // namespace facectl
