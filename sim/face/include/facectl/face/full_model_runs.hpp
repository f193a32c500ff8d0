#pragma once

#include <vector>

#include "facectl/face/face_model.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "facectl/face/steady_state.hpp"

namespace facectl::face {

// The full model's steady-state control-point displacements for many inputs at once, as
// full_model_response() gives them one at a time. Each run starts from rest on its own
// FaceData, so a run's result does not depend on which thread ran it or what ran before:
// any thread count gives the same numbers, bit for bit.
struct FullModelRuns {
  std::vector<std::vector<double>> responses;  // per sample: 3 per control point (m)
  std::vector<SteadyStateResult> settled;      // per sample: how its run ended
};

// `threads` <= 0: one per core (std::thread::hardware_concurrency). An exception in a run
// is rethrown here, after every thread has stopped.
FullModelRuns run_full_model(const FaceModel& m, const std::vector<int>& control_landmarks,
                             const std::vector<ReducedSample>& samples,
                             const SteadyStateOptions& steady, int threads);

// The thread count `threads` asks for: itself if positive, else the machine's cores.
int worker_threads(int threads);

}  // namespace facectl::face
