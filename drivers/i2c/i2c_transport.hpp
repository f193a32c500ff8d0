#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace facectl {

// The SMBus transfers a register-based I2C device needs, addressed by 7-bit
// device address. The seam between a driver and either a real adapter
// (I2cDevTransport over /dev/i2c-N) or a simulated twin. Blocking: only an
// I/O thread calls it. Each call returns 0 (or the byte read) on success and
// -errno on failure (ENXIO / EREMOTEIO: no ACK; EIO: bus error).
class I2cTransport {
 public:
  // Largest SMBus "I2C block" transfer (I2C_SMBUS_BLOCK_MAX).
  static constexpr std::size_t kMaxBlock = 32;

  virtual ~I2cTransport() = default;
  virtual int write_byte(int address, std::uint8_t reg, std::uint8_t value) = 0;
  // Writes data[0] to reg, data[1] to the next register the device selects
  // (with auto-increment: reg + 1), ...; at most kMaxBlock bytes.
  virtual int write_block(int address, std::uint8_t reg, std::span<const std::uint8_t> data) = 0;
  virtual int read_byte(int address, std::uint8_t reg) = 0;
  // The adapter, for messages ("/dev/i2c-1").
  virtual std::string where() const = 0;
};

}  // namespace facectl
