// Running the full face to a steady state under a held input, instead of for a fixed
// number of frames: offline code (fitting, acceptance tests, studies), not the tick.
#pragma once

#include "facectl/face/face_model.hpp"

namespace facectl::face {

struct SteadyStateOptions {
  double tolerance_mm = 0.01;
  int window = 20;
  int min_frames = 60;
  int max_frames = 2000;
  SolverPasses passes;  // a frame's constraint passes (face_model.hpp)
};

struct SteadyStateResult {
  int frames = 0;          // frames stepped by this call
  double residual_mm = 0;  // at the last frame (see run_to_steady_state)
  bool converged = false;
};

// Steps from d's current state with `in` held until the residual is below tolerance_mm,
// or max_frames. The residual at frame t is the largest distance, over the skin vertices
// and over the last `window` frames, from where a vertex is now to where it was:
// max_i max_{1≤k≤window} |x_i(t) − x_i(t−k)|. Taking every k of the window (not only
// t − window) also catches a vertex that oscillates with a period dividing the window.
// Converged needs at least max(min_frames, window) frames of this call. Allocates its
// history (window copies of the skin); d is left at the last frame stepped.
SteadyStateResult run_to_steady_state(const FaceModel& m, FaceData& d, const FaceInput& in,
                                      const SteadyStateOptions& o);

}  // namespace facectl::face
