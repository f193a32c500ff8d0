// run_full_model spreads the fit's and check-reduced's full-model runs over threads. The
// shipped reduced model was fitted one run after another on one FaceData, so the runs must
// give what that gave, bit for bit, on any thread count. In CI's TSan step too.
#include "facectl/face/full_model_runs.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "default_head.hpp"

namespace facectl::face {
namespace {

using testing::default_model;
using testing::default_spec;

// Short runs: some settle within the cap and some do not, so the threads' runs differ in
// length and finish out of order.
SteadyStateOptions short_runs() {
  SteadyStateOptions o;
  o.max_frames = 120;
  o.passes = ReduceOptions{}.steady.passes;
  return o;
}

std::vector<ReducedSample> mixed_inputs() {
  std::vector<ReducedSample> s = training_samples(default_spec(), 5, 3, false);
  ReducedSample rest;  // settles at once
  rest.contractions.assign(default_spec().commanded.size(), 0.0);
  s.insert(s.begin() + 2, rest);
  return s;
}

TEST(FullModelRuns, AnyThreadCountGivesTheOneThreadRunsBitForBit) {
  const FaceModel& m = default_model();
  const std::vector<int> cps = m.landmark_indices(default_spec().control_points);
  const std::vector<ReducedSample> samples = mixed_inputs();
  const SteadyStateOptions steady = short_runs();
  // What the fit did before: one FaceData, the runs in turn.
  FaceData d = make_face_data(m);
  std::vector<std::vector<double>> serial;
  std::vector<SteadyStateResult> serial_settled(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k)
    serial.push_back(full_model_response(m, d, cps, samples[k], steady, &serial_settled[k]));
  int settled = 0;
  for (const SteadyStateResult& r : serial_settled) settled += r.converged ? 1 : 0;
  ASSERT_GT(settled, 0);
  ASSERT_LT(settled, static_cast<int>(samples.size())) << "every run settled: make them longer";

  // Not more than two: CI's TSan step runs this beside the serve tests' 1 kHz loops.
  for (int threads : {1, 2}) {
    const FullModelRuns runs = run_full_model(m, cps, samples, steady, threads);
    ASSERT_EQ(runs.responses.size(), samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) {
      EXPECT_EQ(runs.responses[k], serial[k]) << "sample " << k << ", " << threads << " threads";
      EXPECT_EQ(runs.settled[k].frames, serial_settled[k].frames) << "sample " << k;
      EXPECT_EQ(runs.settled[k].converged, serial_settled[k].converged) << "sample " << k;
      EXPECT_EQ(runs.settled[k].residual_mm, serial_settled[k].residual_mm) << "sample " << k;
    }
  }
}

TEST(FullModelRuns, ARunsErrorReachesTheCaller) {
  const FaceModel& m = default_model();
  SteadyStateOptions bad = short_runs();
  bad.window = 0;  // run_to_steady_state refuses it in every run, on both threads
  EXPECT_THROW(run_full_model(m, {}, mixed_inputs(), bad, 2), std::invalid_argument);
}

TEST(FullModelRuns, NoSamplesNoRuns) {
  const FullModelRuns runs = run_full_model(default_model(), {}, {}, short_runs(), 2);
  EXPECT_TRUE(runs.responses.empty());
  EXPECT_TRUE(runs.settled.empty());
}

TEST(FullModelRuns, AThreadCountIsKeptAndNoneMeansAtLeastOne) {
  EXPECT_EQ(worker_threads(3), 3);
  EXPECT_GE(worker_threads(0), 1);
  EXPECT_EQ(worker_threads(-1), worker_threads(0));
}

}  // namespace
}  // namespace facectl::face
