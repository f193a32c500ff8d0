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

}  // namespace facectl
