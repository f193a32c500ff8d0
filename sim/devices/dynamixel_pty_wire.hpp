#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "sim/devices/dynamixel_servo_sim.hpp"
#include "sim/devices/pty_master.hpp"

namespace facectl::sim {

// Faults a test injects into the wire (any thread, any time).
struct DynamixelWireFaults {
  std::atomic<int> mute_id{-1};        // this servo never answers
  std::atomic<int> corrupt_next{0};    // flip a CRC byte in the next N status packets
  std::atomic<bool> echo{false};       // echo each request first, as a half-duplex adapter
  std::atomic<int> extra_delay_us{0};  // on top of each servo's Return Delay Time
};

// Simulated X-series servos on the master side of a pseudo-terminal, on their
// own thread: the driver opens device() as its serial port. Each request is
// parsed with the Protocol 2.0 codec, handed to every servo, and the replies
// sent after each servo's Return Delay Time, one servo after another as on a
// real daisy chain.
class DynamixelPtyWire {
 public:
  explicit DynamixelPtyWire(std::vector<std::unique_ptr<DynamixelServoSim>> servos);
  ~DynamixelPtyWire();
  DynamixelPtyWire(const DynamixelPtyWire&) = delete;
  DynamixelPtyWire& operator=(const DynamixelPtyWire&) = delete;

  const std::string& device() const { return pty_.device(); }
  DynamixelWireFaults& faults() { return faults_; }
  // Runs `f(servo)` on the servo with this ID under the wire's lock.
  template <typename F>
  void with_servo(std::uint8_t id, F&& f) {
    std::lock_guard lock(mutex_);
    for (auto& s : servos_) {
      if (s->id() == id) f(*s);
    }
  }
  std::uint64_t requests() const { return requests_.load(); }
  // Instruction packets seen, by instruction byte (e.g. 0x83 sync write).
  std::uint64_t requests_of(std::uint8_t instruction) const;

 private:
  void run();
  void serve(std::uint8_t id, std::uint8_t instruction, const std::vector<std::uint8_t>& params,
             const std::uint8_t* raw, std::size_t raw_size);

  std::vector<std::unique_ptr<DynamixelServoSim>> servos_;
  std::mutex mutex_;
  PtyMaster pty_;
  DynamixelWireFaults faults_;
  std::atomic<std::uint64_t> requests_{0};
  std::array<std::atomic<std::uint64_t>, 256> by_instruction_{};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl::sim
