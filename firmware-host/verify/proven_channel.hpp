#pragma once

#include <cstddef>
#include <vector>

namespace facectl::verify {

// What a range proof gives for one actuator channel: every admissible face
// drives its effector (before the channel's transform) into [lo, hi] (SI).
// The two witness faces (full face vectors) come within the proof's tolerance
// of lo and hi; they keep the coupled limits the proof used (a point channel's
// proof leaves out those that name signals outside its polynomial).
struct ProvenChannel {
  std::size_t actuator = 0;
  double lo = 0.0, hi = 0.0;
  std::vector<double> at_lo, at_hi;
  bool converged = false;  // the proven bounds within the proof's tolerance of attained values
};

}  // namespace facectl::verify
