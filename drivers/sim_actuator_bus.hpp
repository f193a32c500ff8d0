#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "control/actuator_bus.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl {

// Simulated twin of an actuator bus: one ServoPlant per actuator, stepped in
// the caller's time (real or simulated). Faults can be injected from any
// thread, as a real bus would report them.
class SimActuatorBus final : public ActuatorBus {
 public:
  SimActuatorBus(std::string name, const std::vector<sim::ServoPlantParams>& plants,
                 const std::vector<double>& initial_positions);

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;

  // Fault injection (thread-safe). `reason` must be a static string.
  void inject_fault(const char* reason) { fault_reason_.store(reason, std::memory_order_release); }
  void clear_fault() { fault_reason_.store(nullptr, std::memory_order_release); }

  bool enabled() const { return enabled_.load(std::memory_order_relaxed); }
  std::uint64_t writes_while_disabled() const { return writes_while_disabled_; }
  const sim::ServoPlant& plant(std::size_t i) const { return plants_[i]; }

 private:
  std::string name_;
  std::vector<sim::ServoPlant> plants_;
  std::atomic<bool> enabled_{false};  // any plant enabled
  std::vector<std::uint8_t> plant_enabled_;
  std::atomic<const char*> fault_reason_{nullptr};
  std::uint64_t frames_ = 0;
  std::uint64_t writes_while_disabled_ = 0;
};

}  // namespace facectl
