#include "sim/devices/memory_can_link.hpp"

namespace facectl {

MemoryCanLink::MemoryCanLink(std::size_t depth)
    : to_devices_(depth),
      to_host_(depth),
      host_(new End(to_host_, to_devices_)),
      devices_(new End(to_devices_, to_host_)) {}

bool MemoryCanLink::End::send(const CanFrame& frame) {
  return tx_.try_push(frame);
}

bool MemoryCanLink::End::receive(CanFrame& frame, CanError& error) {
  if (const CanError* e = errors_.front()) {
    error = *e;
    errors_.pop();
    return true;
  }
  const CanFrame* f = rx_.front();
  if (f == nullptr) return false;
  frame = *f;
  error = CanError::kNone;
  rx_.pop();
  return true;
}

}  // namespace facectl
