#include "drivers/i2c/i2c_dev_transport.hpp"

#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

extern "C" {
#include <i2c/smbus.h>
}

namespace facectl {

I2cDevTransport::I2cDevTransport(std::string device) : device_(std::move(device)) {
  fd_ = ::open(device_.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0) {
    throw std::runtime_error("cannot open " + device_ + ": " + std::strerror(errno) +
                             " (is the i2c-dev module loaded, and may this user open it?)");
  }
  unsigned long funcs = 0;
  constexpr unsigned long kNeeded = I2C_FUNC_SMBUS_BYTE_DATA | I2C_FUNC_SMBUS_WRITE_I2C_BLOCK;
  if (::ioctl(fd_, I2C_FUNCS, &funcs) < 0 || (funcs & kNeeded) != kNeeded) {
    ::close(fd_);
    throw std::runtime_error(device_ + ": the adapter lacks SMBus byte-data and I2C-block writes");
  }
}

I2cDevTransport::~I2cDevTransport() {
  if (fd_ >= 0) ::close(fd_);
}

int I2cDevTransport::select(int address) {
  if (address == selected_) return 0;
  // I2C_SLAVE, not I2C_SLAVE_FORCE: never talk past a kernel driver bound to
  // the address (EBUSY then).
  if (::ioctl(fd_, I2C_SLAVE, static_cast<long>(address)) < 0) return -errno;
  selected_ = address;
  return 0;
}

int I2cDevTransport::write_byte(int address, std::uint8_t reg, std::uint8_t value) {
  if (const int rc = select(address); rc < 0) return rc;
  // libi2c returns -errno itself.
  const std::int32_t rc = i2c_smbus_write_byte_data(fd_, reg, value);
  return rc < 0 ? rc : 0;
}

int I2cDevTransport::write_block(int address, std::uint8_t reg,
                                 std::span<const std::uint8_t> data) {
  if (data.size() > kMaxBlock) return -EINVAL;
  if (const int rc = select(address); rc < 0) return rc;
  const std::int32_t rc =
      i2c_smbus_write_i2c_block_data(fd_, reg, static_cast<std::uint8_t>(data.size()), data.data());
  return rc < 0 ? rc : 0;
}

int I2cDevTransport::read_byte(int address, std::uint8_t reg) {
  if (const int rc = select(address); rc < 0) return rc;
  return i2c_smbus_read_byte_data(fd_, reg);
}

}  // namespace facectl
