#pragma once

#include <map>
#include <mutex>
#include <string>

#include "drivers/i2c/i2c_transport.hpp"
#include "sim/devices/pca9685_sim.hpp"

namespace facectl::sim {

// An in-memory I2C bus of simulated PCA9685s, as an I2cTransport: what
// Pca9685Bus talks to offline and in tests. An address with no board, or a
// board set silent, gives -ENXIO (no ACK), as i2c-dev does.
class MemoryI2cBus final : public I2cTransport {
 public:
  void attach(int address) {
    std::lock_guard lock(mutex_);
    boards_[address];
  }
  void set_answering(int address, bool answering);
  // Runs f(Pca9685Sim&) on a board under the bus's lock (tests inspect and
  // inject faults through it). The board must be attached.
  template <typename F>
  auto with(int address, F&& f) {
    std::lock_guard lock(mutex_);
    return f(boards_.at(address).chip);
  }

  int write_byte(int address, std::uint8_t reg, std::uint8_t value) override;
  int write_block(int address, std::uint8_t reg, std::span<const std::uint8_t> data) override;
  int read_byte(int address, std::uint8_t reg) override;
  std::string where() const override { return "simulated I2C bus"; }

 private:
  struct Slot {
    Pca9685Sim chip;
    bool answering = true;
  };
  Slot* find(int address);

  std::mutex mutex_;
  std::map<int, Slot> boards_;
};

}  // namespace facectl::sim
