#include "control/envelope/mandible_envelope.hpp"

#include "control/units.hpp"

namespace facectl {

MandibleEnvelope MandibleEnvelope::design_default() {
  return {{kJawPitchMinDeg * kDeg, kJawPitchMaxDeg * kDeg},
          {-kJawYawMaxDeg * kDeg, kJawYawMaxDeg * kDeg},
          {0.0, kJawProtrusionMaxMm * 1e-3}};
}

bool MandibleEnvelope::within(const MandibleEnvelope& outer) const {
  return outer.pitch.contains(pitch) && outer.yaw.contains(yaw) &&
         outer.protrusion.contains(protrusion);
}

}  // namespace facectl
