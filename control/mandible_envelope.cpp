#include "control/mandible_envelope.hpp"

#include <algorithm>
#include <numbers>

namespace facectl {

MandibleEnvelope MandibleEnvelope::design_default() {
  constexpr double kDeg = std::numbers::pi / 180.0;
  return {{-4 * kDeg, 18 * kDeg}, {-5 * kDeg, 5 * kDeg}, {0.0, 8e-3}};
}

bool MandibleEnvelope::within(const MandibleEnvelope& outer) const {
  return outer.pitch.contains(pitch) && outer.yaw.contains(yaw) &&
         outer.protrusion.contains(protrusion);
}

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
