#include "drivers/sim_actuator_bus.hpp"

#include <stdexcept>

namespace facectl {

SimActuatorBus::SimActuatorBus(std::string name, const std::vector<sim::ServoPlantParams>& plants,
                               const std::vector<double>& initial_positions)
    : name_(std::move(name)) {
  if (plants.size() != initial_positions.size()) {
    throw std::invalid_argument("sim bus: one initial position per plant");
  }
  plants_.reserve(plants.size());
  for (std::size_t i = 0; i < plants.size(); ++i)
    plants_.emplace_back(plants[i], initial_positions[i]);
}

void SimActuatorBus::read(const TickTime& time, std::span<double> positions) {
  for (std::size_t i = 0; i < plants_.size() && i < positions.size(); ++i) {
    plants_[i].advance(time.now_ns);
    positions[i] = plants_[i].measured();
  }
}

void SimActuatorBus::write(const TickTime& time, std::span<const double> positions) {
  if (!enabled()) {
    ++writes_while_disabled_;
    return;
  }
  for (std::size_t i = 0; i < plants_.size() && i < positions.size(); ++i) {
    plants_[i].command(time.now_ns, positions[i]);
  }
  ++frames_;
}

void SimActuatorBus::set_enabled(bool enabled) {
  enabled_.store(enabled, std::memory_order_relaxed);
  for (auto& p : plants_) p.set_enabled(enabled);
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
