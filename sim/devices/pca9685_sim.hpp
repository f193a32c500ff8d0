#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "drivers/protocol/pca9685_registers.hpp"

namespace facectl::sim {

// A simulated NXP PCA9685: its 256-register file with the chip's semantics
// (data sheet section 7.3): power-on values, auto-increment (MODE1 AI) over
// 0x00..0x45 and 0xFA..0xFE (rolling over to 0x00), a block write without AI
// landing on one register, PRE_SCALE written only while SLEEP is set, RESTART
// cleared by writing 1, EXTCLK sticky, ALL_LED writes reaching every channel
// and reading 0. Not thread-safe: MemoryI2cBus serialises access.
class Pca9685Sim {
 public:
  Pca9685Sim() { power_on(); }

  void power_on();  // the power-on reset state (also a brown-out)
  void write(std::uint8_t reg, std::span<const std::uint8_t> bytes);
  std::uint8_t read(std::uint8_t reg) const;

  std::uint8_t reg(std::uint8_t r) const { return regs_[r]; }
  bool sleeping() const { return (regs_[pca9685::kMode1] & pca9685::kMode1Sleep) != 0; }
  double actual_hz() const { return pca9685::frequency_of(regs_[pca9685::kPreScale]); }
  pca9685::LedRegisters led(int channel) const;
  bool full_off(int channel) const { return (led(channel)[3] & pca9685::kLedFull) != 0; }
  // The pulse the output gives, in µs; 0 while full off or asleep.
  double pulse_us(int channel) const;

  // Faults: a chip whose EXTCLK was set by someone else (PRE_SCALE and MODE1
  // then read back unexpected values) or which ignores PRE_SCALE writes.
  void set_ignore_prescale(bool ignore) { ignore_prescale_ = ignore; }

 private:
  void write_one(std::uint8_t reg, std::uint8_t value);
  static std::uint8_t next(std::uint8_t reg);

  std::array<std::uint8_t, 256> regs_{};
  bool ignore_prescale_ = false;
};

}  // namespace facectl::sim
