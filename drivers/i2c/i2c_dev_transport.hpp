#pragma once

#include <string>

#include "drivers/i2c/i2c_transport.hpp"

namespace facectl {

// I2cTransport over Linux i2c-dev (/dev/i2c-N): ioctl(I2C_SLAVE) selects the
// device, libi2c's SMBus calls (<i2c/smbus.h>) move the bytes. SMBus rather
// than I2C_RDWR because that is what every adapter, and the kernel's
// i2c-stub that the QEMU test uses, supports.
class I2cDevTransport final : public I2cTransport {
 public:
  // Throws std::runtime_error naming the device and the reason when it cannot
  // be opened or lacks the SMBus byte and I2C-block functions.
  explicit I2cDevTransport(std::string device);
  ~I2cDevTransport() override;
  I2cDevTransport(const I2cDevTransport&) = delete;
  I2cDevTransport& operator=(const I2cDevTransport&) = delete;

  int write_byte(int address, std::uint8_t reg, std::uint8_t value) override;
  int write_block(int address, std::uint8_t reg, std::span<const std::uint8_t> data) override;
  int read_byte(int address, std::uint8_t reg) override;
  std::string where() const override { return device_; }

 private:
  int select(int address);

  std::string device_;
  int fd_ = -1;
  int selected_ = -1;
};

}  // namespace facectl
