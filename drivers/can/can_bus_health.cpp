#include "drivers/can/can_bus_health.hpp"

namespace facectl {

CanBusHealth::CanBusHealth(const std::string& bus)
    : bus_off_(bus + ": bus-off"),
      passive_(bus + ": error-passive"),
      no_ack_(bus + ": no ACK (no other node on the bus?)"),
      protocol_(bus + ": protocol error frames"),
      tx_full_(bus + ": TX queue full") {}

void CanBusHealth::set(const std::string& reason) {
  set_first_reason(fault_, reason);
}

void CanBusHealth::on_error(CanError e, std::int64_t now_ns) {
  if (e == CanError::kRestarted) {
    if (fault_.load(std::memory_order_relaxed) == bus_off_.c_str()) {
      fault_.store(nullptr, std::memory_order_release);
    }
    return;
  }
  errors_.fetch_add(1, std::memory_order_relaxed);
  if (e != CanError::kWarning && e != CanError::kOverflow) last_error_ns_ = now_ns;
  switch (e) {
    case CanError::kBusOff:
      set(bus_off_);
      break;
    case CanError::kErrorPassive:
      set(passive_);
      break;
    case CanError::kNoAck:
      set(no_ack_);
      break;
    case CanError::kProtocol:
      set(protocol_);
      break;
    default:
      break;
  }
}

void CanBusHealth::on_send(bool accepted) {
  if (accepted) {
    sent_.fetch_add(1, std::memory_order_relaxed);
  } else {
    refused_.fetch_add(1, std::memory_order_relaxed);
    refused_this_cycle_ = true;
  }
}

void CanBusHealth::end_cycle(std::int64_t now_ns) {
  full_cycles_ = refused_this_cycle_ ? full_cycles_ + 1 : 0;
  refused_this_cycle_ = false;
  if (full_cycles_ >= kTxFullCycles) {
    set(tx_full_);
    last_error_ns_ = now_ns;
  }
  const char* f = fault_.load(std::memory_order_relaxed);
  if (f != nullptr && f != bus_off_.c_str() && now_ns - last_error_ns_ > kHoldNs) {
    fault_.store(nullptr, std::memory_order_release);
  }
}

BusStatus CanBusHealth::status(const char* device_fault, std::uint64_t bad_frames) const {
  BusStatus s;
  const char* r = fault() != nullptr ? fault() : device_fault;
  s.fault = r != nullptr;
  s.reason = r != nullptr ? r : "";
  s.frames_sent = frames_sent();
  s.errors = errors() + tx_refused() + bad_frames;
  return s;
}

void set_first_reason(std::atomic<const char*>& slot, const std::string& reason) {
  const char* expected = nullptr;
  slot.compare_exchange_strong(expected, reason.c_str(), std::memory_order_acq_rel);
}

}  // namespace facectl
