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

// Step 4 of the tick: clamps the mandible to its envelope and every other
// rigid DOF to the head's admissible range. Counts what it clamped.
class FaceEnvelope {
 public:
  enum Flag : std::uint8_t {
    kPitchClamped = 1 << 0,
    kYawClamped = 1 << 1,
    kProtrusionClamped = 1 << 2,
    kRigidClamped = 1 << 3,
  };

  FaceEnvelope(const FaceLayout& layout, const MandibleEnvelope& mandible,
               const std::array<Range, kMaxFaceSignals>& admissible);

  // Clamps `values` in place; returns the Flag bits of what fired.
  std::uint8_t apply(std::array<double, kMaxFaceSignals>& values);

  const MandibleEnvelope& mandible() const { return mandible_; }
  std::uint64_t clamp_count() const { return clamp_count_; }

 private:
  const FaceLayout& layout_;
  MandibleEnvelope mandible_;
  std::array<Range, kMaxFaceSignals> admissible_;
  std::uint64_t clamp_count_ = 0;
};

}  // namespace facectl
