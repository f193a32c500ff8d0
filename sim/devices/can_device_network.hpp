#pragma once

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "sim/devices/can_device.hpp"

namespace facectl::sim {

// Simulated devices sharing one CAN transport: an in-process MemoryCanLink
// end, or a SocketCAN socket on vcan (the QEMU test). poll() delivers what
// arrived to every device, steps them, and sends what is due; start() does
// that on a thread every `period_us` in real time.
class CanDeviceNetwork {
 public:
  CanDeviceNetwork(CanTransport& transport, std::vector<CanDevice*> devices);
  ~CanDeviceNetwork();

  void poll(std::int64_t now_ns);
  void start(int period_us);
  void stop();
  std::uint64_t frames_sent() const { return sent_.load(); }

 private:
  CanTransport& transport_;
  std::vector<CanDevice*> devices_;
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl::sim
