#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "control/command/face_layout.hpp"

namespace facectl {

struct Range {
  double min = 0.0;
  double max = 0.0;
  bool contains(const Range& inner) const { return inner.min >= min && inner.max <= max; }
};

// The mandible's joint limits: the product's hard envelope, in the units head
// and rig files write. Pitch -4..18 deg and yaw ±5 deg are the clamp of the
// anatomical face model this controller follows (docs/FACE_MODEL.md); adults
// protrude the mandible about 7-10 mm at most, so 0..8 mm stays below the
// anatomical maximum and never retrudes behind rest.
inline constexpr double kJawPitchMinDeg = -4, kJawPitchMaxDeg = 18;
inline constexpr double kJawYawMaxDeg = 5;  // either side
inline constexpr double kJawProtrusionMaxMm = 8;

// The mandible's safety envelope, SI units (rad, rad, m).
struct MandibleEnvelope {
  Range pitch;
  Range yaw;
  Range protrusion;

  // The joint limits above, in SI.
  static MandibleEnvelope design_default();

  // True if every range lies inside `outer`.
  bool within(const MandibleEnvelope& outer) const;
};

}  // namespace facectl
