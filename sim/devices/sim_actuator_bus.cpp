#include "sim/devices/sim_actuator_bus.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace facectl {

SimActuatorBus::SimActuatorBus(std::string name, const std::vector<sim::ServoPlantParams>& plants,
                               const std::vector<double>& initial_positions,
                               const SimBusTiming& timing)
    : name_(std::move(name)), timing_(timing.timing) {
  if (plants.size() != initial_positions.size()) {
    throw std::invalid_argument("sim bus: one initial position per plant");
  }
  if (!timing.arrival_s.empty() && timing.arrival_s.size() != plants.size()) {
    throw std::invalid_argument("sim bus: one arrival time per plant");
  }
  plants_.reserve(plants.size());
  transfer_ns_.assign(plants.size(), 0);
  for (std::size_t i = 0; i < plants.size(); ++i) {
    plants_.emplace_back(plants[i], initial_positions[i]);
    if (!timing.arrival_s.empty()) {
      transfer_ns_[i] = static_cast<std::int64_t>(timing.arrival_s[i] * 1e9 + 0.5);
    }
  }
  plant_enabled_.assign(plants.size(), 0);
  scripted_.assign(plants.size(), ActuatorHealth{});
  for (const auto& p : plants) reports_health_.push_back(p.thermal.full_effort > 0.0 ? 1 : 0);
}

void SimActuatorBus::read_health(std::span<ActuatorHealth> health) {
  const std::size_t n = std::min(plants_.size(), health.size());
  for (std::size_t i = 0; i < n; ++i) {
    ActuatorHealth h;
    if (reports_health_[i] != 0) {
      h.temperature_c = plants_[i].temperature_c();
      h.load = plants_[i].load();
    }
    const ActuatorHealth& s = scripted_[i];
    const auto pick = [](double scripted, double own) {
      return std::isnan(scripted) ? own : scripted;
    };
    h.temperature_c = pick(s.temperature_c, h.temperature_c);
    h.load = pick(s.load, h.load);
    h.current_a = pick(s.current_a, h.current_a);
    h.voltage_v = pick(s.voltage_v, h.voltage_v);
    h.hardware_error = s.hardware_error;
    health[i] = h;
  }
}

void SimActuatorBus::read(const TickTime& time, std::span<double> positions) {
  // Latched: the first overloaded servo names the fault until it is cleared.
  if (const char* overload = sim::advance_and_measure(plants_, time.now_ns, positions)) {
    const char* none = nullptr;
    fault_reason_.compare_exchange_strong(none, overload, std::memory_order_release);
  }
}

void SimActuatorBus::clear_fault() {
  for (auto& p : plants_) p.clear_fault();
  fault_reason_.store(nullptr, std::memory_order_release);
}

void SimActuatorBus::write(const TickTime& time, std::span<const double> positions) {
  if (!enabled()) {
    ++writes_while_disabled_;
    return;
  }
  // Locals: the compiler cannot tell that commanding a plant leaves the
  // vectors alone, and would reload them for every servo.
  const std::size_t n = std::min(plants_.size(), positions.size());
  const std::int64_t now_ns = time.now_ns;
  sim::ServoPlant* plants = plants_.data();
  const std::uint8_t* enabled = plant_enabled_.data();
  const std::int64_t* transfer_ns = transfer_ns_.data();
  for (std::size_t i = 0; i < n; ++i) {
    if (enabled[i] != 0) plants[i].command(now_ns + transfer_ns[i], positions[i]);
  }
  ++frames_;
}

void SimActuatorBus::set_enabled(bool enabled) {
  enabled_.store(enabled, std::memory_order_relaxed);
  for (std::size_t i = 0; i < plants_.size(); ++i) {
    plant_enabled_[i] = enabled ? 1 : 0;
    plants_[i].set_enabled(enabled);
  }
}

void SimActuatorBus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  bool any = false;
  for (std::size_t i = 0; i < plants_.size(); ++i) {
    const bool on = i < enabled.size() && enabled[i] != 0;
    plant_enabled_[i] = on ? 1 : 0;
    plants_[i].set_enabled(on);
    any = any || on;
  }
  enabled_.store(any, std::memory_order_relaxed);
}

BusStatus SimActuatorBus::status() const {
  BusStatus s;
  const char* reason = fault_reason_.load(std::memory_order_acquire);
  s.fault = reason != nullptr;
  s.reason = reason != nullptr ? reason : "";
  s.frames_sent = frames_;
  return s;
}

}  // namespace facectl
