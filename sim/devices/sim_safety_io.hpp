#pragma once

#include <atomic>

#include "control/actuator_bus.hpp"

namespace facectl {

// Simulated twin of the GPIO safety I/O: an e-stop line that tests (or
// `facectl run --inject`) press and release, and a power-enable output whose
// state they can observe.
class SimSafetyIo final : public SafetyIo {
 public:
  bool estop_active() override { return estop_.load(std::memory_order_acquire); }
  void set_power_enable(bool on) override { power_.store(on, std::memory_order_release); }
  bool fault() const override { return fault_.load(std::memory_order_acquire); }

  void press_estop() { estop_.store(true, std::memory_order_release); }
  void release_estop() { estop_.store(false, std::memory_order_release); }
  void inject_fault(bool on) { fault_.store(on, std::memory_order_release); }
  bool power_enabled() const { return power_.load(std::memory_order_acquire); }

 private:
  std::atomic<bool> estop_{false};
  std::atomic<bool> power_{false};
  std::atomic<bool> fault_{false};
};

}  // namespace facectl
