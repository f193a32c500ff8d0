// Full-model runs spread over threads: the fit's and check-reduced's cost is thousands of
// independent runs to a steady state (16 minutes on one core for `face reduce`).
#include "facectl/face/full_model_runs.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

namespace facectl::face {

int worker_threads(int threads) {
  if (threads > 0) return threads;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

FullModelRuns run_full_model(const FaceModel& m, const std::vector<int>& control_landmarks,
                             const std::vector<ReducedSample>& samples,
                             const SteadyStateOptions& steady, int threads) {
  FullModelRuns out;
  out.responses.resize(samples.size());
  out.settled.resize(samples.size());
  // Runs differ in length (an input that does not settle runs to the frame cap), so each
  // thread takes the next sample when it is free rather than a fixed share.
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    try {
      FaceData d = make_face_data(m);
      for (std::size_t k = next++; k < samples.size() && !failed.load(); k = next++)
        out.responses[k] =
            full_model_response(m, d, control_landmarks, samples[k], steady, &out.settled[k]);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed.store(true);
    }
  };
  const int n = std::min(worker_threads(threads), static_cast<int>(samples.size()));
  std::vector<std::thread> pool;
  try {
    for (int t = 1; t < n; ++t) pool.emplace_back(work);
  } catch (...) {  // no more threads: stop the ones started before rethrowing
    failed.store(true);
    for (std::thread& t : pool) t.join();
    throw;
  }
  work();  // this thread is one of the n
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return out;
}

}  // namespace facectl::face
