#include "control/envelope/face_envelope.hpp"

#include <algorithm>

namespace facectl {

FaceEnvelope::FaceEnvelope(const FaceLayout& layout, const MandibleEnvelope& mandible,
                           const std::array<Range, kMaxFaceSignals>& admissible)
    : layout_(layout), mandible_(mandible), admissible_(admissible) {
  // The mandible's envelope overrides whatever admissible range it was given.
  admissible_[layout.jaw_pitch()] = mandible.pitch;
  admissible_[layout.jaw_yaw()] = mandible.yaw;
  admissible_[layout.jaw_protrusion()] = mandible.protrusion;
}

std::uint8_t FaceEnvelope::apply(std::array<double, kMaxFaceSignals>& values) {
  std::uint8_t flags = 0;
  for (std::size_t i = layout_.muscle_count(); i < layout_.size(); ++i) {
    const Range& r = admissible_[i];
    const double clamped = std::clamp(values[i], r.min, r.max);
    if (clamped == values[i]) continue;
    values[i] = clamped;
    if (i == layout_.jaw_pitch()) {
      flags |= kPitchClamped;
    } else if (i == layout_.jaw_yaw()) {
      flags |= kYawClamped;
    } else if (i == layout_.jaw_protrusion()) {
      flags |= kProtrusionClamped;
    } else {
      flags |= kRigidClamped;
    }
  }
  if (flags != 0) ++clamp_count_;
  return flags;
}

}  // namespace facectl
