#pragma once

#include <array>
#include <atomic>
#include <exception>
#include <span>
#include <thread>

#include "control/spsc_ring.hpp"
#include "control/telemetry_record.hpp"
#include "firmware-host/simulate/simulation_run.hpp"

namespace facectl {

// Feeds each tick's telemetry record and simulated actuator positions to the
// simulation's sinks (statistics, telemetry file, plot columns, progress), in
// tick order. With `threaded`, a second thread runs the sinks while the head
// goes on ticking, so writing the outputs overlaps the simulation; without,
// push() runs them at once. The sinks see the same ticks in the same order
// either way, so the outputs are the same bytes; only the wall time differs.
// Nothing is dropped: the producer waits for room instead.
class OutputPipeline {
 public:
  // `telemetry`: the ring the head's Controller publishes one record a tick to.
  OutputPipeline(SpscRing<TelemetryRecord>& telemetry, const SimulationSinks& sinks,
                 std::size_t actuators, bool threaded);
  ~OutputPipeline();
  OutputPipeline(const OutputPipeline&) = delete;
  OutputPipeline& operator=(const OutputPipeline&) = delete;

  // Before a tick: returns once the telemetry ring has room for its record.
  void wait_for_room();
  // After a tick (whose record the Controller published): hands over its show
  // time and the simulated positions.
  void push(double t, std::span<const double> positions);
  // Returns once every tick handed over went through the sinks; rethrows what
  // a sink threw.
  void finish();
  // A sink threw: stop ticking, finish() rethrows it.
  bool failed() const { return failed_.load(std::memory_order_acquire); }

  // Whether a second thread is worth it here (more than one CPU).
  static bool worth_threading();

 private:
  struct Sample {
    double t = 0.0;
    std::array<double, kMaxActuators> positions{};
  };

  void consume_one();
  void work();

  SpscRing<TelemetryRecord>& telemetry_;
  const SimulationSinks& sinks_;
  std::size_t actuators_;
  SpscRing<Sample> samples_;
  std::atomic<bool> done_{false};
  std::atomic<bool> failed_{false};
  std::exception_ptr error_;  // written by the worker before failed_, read after join
  std::thread worker_;
};

}  // namespace facectl
