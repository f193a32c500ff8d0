#include "sim/devices/sim_gpio_chip.hpp"

#include <stdexcept>
#include <string>

namespace facectl {

SimGpioChip::SimGpioChip(unsigned lines) : lines_(lines) {
  for (auto& l : lines_) l.queue.reserve(64);
}

int SimGpioChip::request_input(unsigned offset, bool active_low, const char* /*consumer*/) {
  std::lock_guard lock(mutex_);
  if (offset >= lines_.size() || lines_[offset].requested) {
    throw std::runtime_error("GPIO simulated chip line " + std::to_string(offset) +
                             " cannot be requested");
  }
  lines_[offset].requested = true;
  lines_[offset].active_low = active_low;
  handles_.push_back(offset);
  return static_cast<int>(handles_.size() - 1);
}

int SimGpioChip::request_output(unsigned offset, bool active_low, bool initial,
                                const char* consumer) {
  const int h = request_input(offset, active_low, consumer);
  std::lock_guard lock(mutex_);
  lines_[offset].output = true;
  lines_[offset].high = initial != active_low;
  return h;
}

int SimGpioChip::read_edges(int handle, std::span<GpioEdge> out) {
  std::lock_guard lock(mutex_);
  Line& l = lines_[handles_[static_cast<std::size_t>(handle)]];
  if (l.gone) return -1;
  const std::size_t n = std::min(out.size(), l.queue.size());
  for (std::size_t i = 0; i < n; ++i) out[i] = l.queue[i];
  l.queue.erase(l.queue.begin(), l.queue.begin() + static_cast<std::ptrdiff_t>(n));
  return static_cast<int>(n);
}

int SimGpioChip::get_value(int handle) {
  std::lock_guard lock(mutex_);
  const Line& l = lines_[handles_[static_cast<std::size_t>(handle)]];
  if (l.gone) return -1;
  return l.high != l.active_low ? 1 : 0;
}

bool SimGpioChip::set_value(int handle, bool active) {
  std::lock_guard lock(mutex_);
  Line& l = lines_[handles_[static_cast<std::size_t>(handle)]];
  if (l.gone) return false;
  l.high = active != l.active_low;
  return true;
}

void SimGpioChip::set_physical(unsigned offset, bool high) {
  std::lock_guard lock(mutex_);
  Line& l = lines_.at(offset);
  if (l.high == high) return;
  l.high = high;
  if (l.requested && l.queue.size() < 64) l.queue.push_back({high != l.active_low});
}

bool SimGpioChip::physical(unsigned offset) const {
  std::lock_guard lock(mutex_);
  return lines_.at(offset).high;
}

void SimGpioChip::remove_line(unsigned offset) {
  std::lock_guard lock(mutex_);
  lines_.at(offset).gone = true;
}

}  // namespace facectl
