#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "control/face_layout.hpp"

namespace facectl {

struct Range {
  double min = 0.0;
  double max = 0.0;
  bool contains(const Range& inner) const { return inner.min >= min && inner.max <= max; }
};

// The mandible's safety envelope, SI units (rad, rad, m).
struct MandibleEnvelope {
  Range pitch;
  Range yaw;
  Range protrusion;

  // Design defaults. Pitch and yaw are the thesis's clamp (reference/face-model-pbd.md
  // §4, items 9 and 4 of §9-10). Protrusion: adults protrude the mandible about
  // 7-10 mm at most (reference/facial-animation-tutorial.md L98), so 0..8 mm
  // keeps below the anatomical maximum and never retrudes behind rest.
  static MandibleEnvelope design_default();

  // True if every range lies inside `outer`.
  bool within(const MandibleEnvelope& outer) const;
};

}  // namespace facectl
