#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "control/actuator_bus.hpp"
#include "sim/devices/sim_bus_timing.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl {

// Simulated twin of an actuator bus: one ServoPlant per actuator, stepped in
// the caller's time (real or simulated). A command reaches its plant after its
// bus transfer time (`timing.arrival_s`; none if empty), then the plant's own
// latency. A plant's overload fault is reported as the bus's fault, as a smart
// servo reports it; faults can also be injected from any thread.
class SimActuatorBus final : public ActuatorBus {
 public:
  SimActuatorBus(std::string name, const std::vector<sim::ServoPlantParams>& plants,
                 const std::vector<double>& initial_positions, const SimBusTiming& timing = {});

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;
  // Each plant's thermal model's temperature and load (when it has one, as
  // for a smart servo), overridden by scripted health.
  void read_health(std::span<ActuatorHealth> health) override;

  // Test hooks, from the thread that steps the bus: health that replaces the
  // plant's (its non-NaN fields; hardware_error as given), and an obstacle.
  void script_health(std::size_t i, const ActuatorHealth& h) { scripted_[i] = h; }
  void block_above(std::size_t i, double stop) { plants_[i].block_above(stop); }

  // Fault injection (thread-safe). `reason` must be a static string.
  void inject_fault(const char* reason) { fault_reason_.store(reason, std::memory_order_release); }
  // Also resets the plants' latched overload faults: call it from the thread
  // that steps the bus.
  void clear_fault();

  bool enabled() const { return enabled_.load(std::memory_order_relaxed); }
  std::uint64_t writes_while_disabled() const { return writes_while_disabled_; }
  const sim::ServoPlant& plant(std::size_t i) const { return plants_[i]; }
  std::size_t plant_count() const { return plants_.size(); }
  const BusTiming& timing() const { return timing_; }

 private:
  std::string name_;
  std::vector<sim::ServoPlant> plants_;
  std::vector<std::int64_t> transfer_ns_;  // per plant: bus time to reach it
  BusTiming timing_;
  std::atomic<bool> enabled_{false};  // any plant enabled
  std::vector<std::uint8_t> plant_enabled_;
  std::vector<ActuatorHealth> scripted_;
  std::vector<std::uint8_t> reports_health_;  // the plant has a thermal model
  std::atomic<const char*> fault_reason_{nullptr};
  std::uint64_t frames_ = 0;
  std::uint64_t writes_while_disabled_ = 0;
};

}  // namespace facectl
