#include "facectl/face/steady_state.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace facectl::face {

SteadyStateResult run_to_steady_state(const FaceModel& m, FaceData& d, const FaceInput& in,
                                      const SteadyStateOptions& o) {
  if (o.window < 1 || o.max_frames < 0 || !(o.tolerance_mm > 0))
    throw std::invalid_argument(
        "run_to_steady_state: needs window >= 1, max_frames >= 0 and tolerance_mm > 0");
  // Ring of the last `window` skin states, slot f % window holding frame f's.
  const std::size_t n = d.skin_x.size();
  const int w = o.window;
  std::vector<Points> ring(static_cast<std::size_t>(w));
  const double tol2 = (o.tolerance_mm * 1e-3) * (o.tolerance_mm * 1e-3);
  SteadyStateResult r;
  for (int f = 1; f <= o.max_frames; ++f) {
    Points& slot = ring[static_cast<std::size_t>((f - 1) % w)];
    slot = d.skin_x;  // frame f − 1's state (the first is the state handed in)
    step_face(m, d, in, o.passes);
    r.frames = f;
    // Until the window is full the residual covers the frames there are, but cannot
    // converge.
    double worst2 = 0;
    const Points& x = d.skin_x;
    for (int s = 0; s < std::min(f, w); ++s) {
      const Points& h = ring[static_cast<std::size_t>(s)];
      for (std::size_t i = 0; i < n; ++i) {
        const double dx = x.x[i] - h.x[i], dy = x.y[i] - h.y[i], dz = x.z[i] - h.z[i];
        worst2 = std::max(worst2, dx * dx + dy * dy + dz * dz);
      }
    }
    r.residual_mm = 1e3 * std::sqrt(worst2);
    if (f >= std::max(o.min_frames, w) && worst2 < tol2) {
      r.converged = true;
      break;
    }
  }
  return r;
}

}  // namespace facectl::face
