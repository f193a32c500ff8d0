// The simulation loop allocates nothing per tick: with every output sink
// attached (statistics, decimated telemetry, plot columns), simulating three
// times longer makes exactly as many allocations (set-up and the first write
// only).
#include <gtest/gtest.h>

#include "firmware-host/simulate/actuator_plots.hpp"
#include "firmware-host/simulate/decimated_telemetry.hpp"
#include "firmware-host/simulate/simulation_run.hpp"
#include "firmware-host/simulate/simulation_stats.hpp"
#include "simulate_process.hpp"
#include "tests/support/allocation_counter.hpp"

namespace facectl {
namespace {

long allocations_for(const LoadedConfig& cfg, const SimulationInput& input, double seconds,
                     const std::string& csv) {
  OfflineHead head(cfg, 8);
  SimulationStats stats(head.model());
  DecimatedTelemetry telemetry(head.model(), csv, 10);
  ActuatorPlots plots(head.model(), seconds);
  const SimulationSinks sinks{&stats, &telemetry, &plots, nullptr, {}, 25.0};
  testing::begin_counting_allocations();
  (void)run_simulation(head, input, seconds, sinks);
  const long n = testing::end_counting_allocations();
  telemetry.close();
  return n;
}

TEST(SimulateAllocations, NoneDependOnTheLengthOfTheShow) {
  testing::TempDir tmp;
  const LoadedConfig cfg = load_config(default_config_path());
  for (const SimulationInput& input :
       {SimulationInput::from_show(*cfg.show),
        SimulationInput::load_fap(cfg, std::string(FAP_TEST_FILES) + "/good.fap")}) {
    const long short_run = allocations_for(cfg, input, 1.0, tmp / "a.csv");
    const long long_run = allocations_for(cfg, input, 3.0, tmp / "b.csv");
    EXPECT_EQ(short_run, long_run) << input.kind() << ": allocations grow with simulated time";
    EXPECT_LT(short_run, 20) << input.kind();
  }
}

}  // namespace
}  // namespace facectl
