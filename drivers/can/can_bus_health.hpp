#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "control/actuator_bus.hpp"
#include "drivers/can/can_transport.hpp"

namespace facectl {

// The health of one CAN bus as the tick sees it: error frames, controller
// states and a TX queue that keeps refusing frames. Bus-off, error-passive,
// missing ACKs and protocol errors are faults, each with its own reason;
// warnings and overflows are counted. Never blocks, never allocates after
// construction. A fault clears once its condition has gone: bus-off when the
// controller reports its restart, the others after kHoldNs without a new
// error frame. The safety state machine latches FAULT regardless.
class CanBusHealth {
 public:
  explicit CanBusHealth(const std::string& bus);

  void on_error(CanError e, std::int64_t now_ns);
  // A refused frame: the TX queue is full. A queue full for `kTxFullCycles`
  // cycles in a row is a fault (nobody is taking frames off the bus).
  void on_send(bool accepted);
  void end_cycle(std::int64_t now_ns);

  const char* fault() const { return fault_.load(std::memory_order_acquire); }
  std::uint64_t frames_sent() const { return sent_.load(std::memory_order_relaxed); }
  std::uint64_t errors() const { return errors_.load(std::memory_order_relaxed); }
  std::uint64_t tx_refused() const { return refused_.load(std::memory_order_relaxed); }

  // The bus's status: this health's fault first (it explains the devices'
  // silence), else the first device fault; errors include `bad_frames`.
  BusStatus status(const char* device_fault, std::uint64_t bad_frames) const;

  static constexpr int kTxFullCycles = 50;
  static constexpr std::int64_t kHoldNs = 500'000'000;

 private:
  void set(const std::string& reason);

  std::string bus_off_, passive_, no_ack_, protocol_, tx_full_;
  std::atomic<const char*> fault_{nullptr};
  std::atomic<std::uint64_t> sent_{0}, errors_{0}, refused_{0};
  bool refused_this_cycle_ = false;
  int full_cycles_ = 0;
  std::int64_t last_error_ns_ = 0;
};

// Stores `reason` unless a reason is already there: the first one is the cause.
void set_first_reason(std::atomic<const char*>& slot, const std::string& reason);

}  // namespace facectl
