#pragma once

#include <array>
#include <cstdint>

#include "control/capacity.hpp"
#include "control/command/face_layout.hpp"
#include "control/envelope/mandible_envelope.hpp"

namespace facectl {

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
