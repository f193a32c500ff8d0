#pragma once

#include <cstddef>
#include <vector>

namespace facectl::verify {

// What a range proof gives for one actuator channel: every admissible face
// drives its effector (before the channel's transform) into [lo, hi] (SI),
// attained at the two witness faces (full face vectors).
struct ProvenChannel {
  std::size_t actuator = 0;
  double lo = 0.0, hi = 0.0;
  std::vector<double> at_lo, at_hi;
  bool converged = false;  // the proven bounds within the proof's tolerance of attained values
};

}  // namespace facectl::verify
