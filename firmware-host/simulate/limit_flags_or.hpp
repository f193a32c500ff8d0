#pragma once

#include <array>

#include "control/actuator_model.hpp"
#include "control/capacity.hpp"

namespace facectl {

// into[i] |= flags[i] for all kMaxActuators entries (those past the rig's
// actuator count are 0 or unused): gathering a tick's limiter flags into a
// telemetry row or a plot column. The local copy tells the compiler that the
// two arrays do not overlap, so the fixed-count loop becomes a few vector ORs
// (without it, a scalar loop five instructions an entry).
inline void or_limit_flags(std::array<LimitFlags, kMaxActuators>& into,
                           const std::array<LimitFlags, kMaxActuators>& flags) {
  const std::array<LimitFlags, kMaxActuators> copy = flags;
  for (std::size_t i = 0; i < kMaxActuators; ++i) into[i] |= copy[i];
}

}  // namespace facectl
