#include "sim/devices/memory_i2c_bus.hpp"

#include <cerrno>

namespace facectl::sim {

void MemoryI2cBus::set_answering(int address, bool answering) {
  std::lock_guard lock(mutex_);
  boards_.at(address).answering = answering;
}

MemoryI2cBus::Slot* MemoryI2cBus::find(int address) {
  const auto it = boards_.find(address);
  return it == boards_.end() || !it->second.answering ? nullptr : &it->second;
}

int MemoryI2cBus::write_byte(int address, std::uint8_t reg, std::uint8_t value) {
  return write_block(address, reg, std::span(&value, 1));
}

int MemoryI2cBus::write_block(int address, std::uint8_t reg, std::span<const std::uint8_t> data) {
  if (data.size() > kMaxBlock) return -EINVAL;
  std::lock_guard lock(mutex_);
  Slot* s = find(address);
  if (s == nullptr) return -ENXIO;
  s->chip.write(reg, data);
  return 0;
}

int MemoryI2cBus::read_byte(int address, std::uint8_t reg) {
  std::lock_guard lock(mutex_);
  Slot* s = find(address);
  return s == nullptr ? -ENXIO : s->chip.read(reg);
}

}  // namespace facectl::sim
