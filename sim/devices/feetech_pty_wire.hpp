#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "sim/devices/feetech_servo_sim.hpp"
#include "sim/devices/pty_master.hpp"

namespace facectl::sim {

// Faults a test injects into the wire (any thread, any time).
struct FeetechWireFaults {
  std::atomic<int> mute_id{-1};      // this servo never answers
  std::atomic<int> corrupt_next{0};  // spoil the checksum of the next N status packets
  std::atomic<bool> echo{false};     // echo each request first, as a half-duplex adapter
};

// Simulated Feetech servos on the master side of a pseudo-terminal, on their
// own thread: the driver opens device() as its serial port. Each request is
// parsed with the Feetech codec and handed to every servo; the replies go
// out after each servo's Return Delay, one servo after another.
class FeetechPtyWire {
 public:
  explicit FeetechPtyWire(std::vector<std::unique_ptr<FeetechServoSim>> servos);
  ~FeetechPtyWire();
  FeetechPtyWire(const FeetechPtyWire&) = delete;
  FeetechPtyWire& operator=(const FeetechPtyWire&) = delete;

  const std::string& device() const { return pty_.device(); }
  FeetechWireFaults& faults() { return faults_; }
  template <typename F>
  void with_servo(std::uint8_t id, F&& f) {
    std::lock_guard lock(mutex_);
    for (auto& s : servos_) {
      if (s->id() == id) f(*s);
    }
  }
  // Instruction packets seen, by instruction byte (e.g. 0x83 sync write).
  std::uint64_t requests_of(std::uint8_t instruction) const {
    return by_instruction_[instruction].load();
  }

 private:
  void run();
  void serve(std::uint8_t id, std::uint8_t instruction, const std::vector<std::uint8_t>& params,
             const std::uint8_t* raw, std::size_t raw_size);

  std::vector<std::unique_ptr<FeetechServoSim>> servos_;
  std::mutex mutex_;
  PtyMaster pty_;
  FeetechWireFaults faults_;
  std::array<std::atomic<std::uint64_t>, 256> by_instruction_{};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl::sim
