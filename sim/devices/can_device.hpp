#pragma once

#include <atomic>
#include <cstdint>
#include <deque>

#include "drivers/can/can_transport.hpp"

namespace facectl::sim {

// Faults a test injects into one simulated CAN device (any thread).
struct CanDeviceFaults {
  std::atomic<bool> silent{false};   // neither answers nor acts on frames: power lost
  std::atomic<int> drop_every{0};    // drop every Nth frame it sends
  std::atomic<int> corrupt_next{0};  // send the next N frames one byte short
  std::atomic<int> delay_ms{0};      // hold every frame it sends this long
};

// A simulated device on a CAN bus, stepped by CanDeviceNetwork in the
// network's time. Frames it sends pass through its fault injection.
class CanDevice {
 public:
  virtual ~CanDevice() = default;
  // A frame seen on the bus (every device sees every frame).
  virtual void on_frame(const CanFrame& f, std::int64_t now_ns) = 0;
  // The device's own loop: plants, heartbeats, watchdogs.
  virtual void step(std::int64_t now_ns) = 0;

  CanDeviceFaults& faults() { return faults_; }

 protected:
  // Queues a frame for the bus through the fault injection.
  void emit(const CanFrame& f, std::int64_t now_ns);

 private:
  friend class CanDeviceNetwork;
  struct Pending {
    std::int64_t at_ns;
    CanFrame frame;
  };
  CanDeviceFaults faults_;
  std::deque<Pending> outbox_;
  std::uint64_t emitted_ = 0;
};

}  // namespace facectl::sim
