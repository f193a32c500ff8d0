#include "sim/devices/modbus_actuator_board.hpp"

#include <stdexcept>

namespace facectl::sim {

using namespace modbus_map;

ModbusActuatorBoard::ModbusActuatorBoard(int unit, std::vector<BoardChannel> channels)
    : unit_(unit), spec_(std::move(channels)) {
  if (spec_.empty() || spec_.size() > static_cast<std::size_t>(kChannelsPerBoard)) {
    throw std::invalid_argument("simulated Modbus board: 1..8 channels");
  }
  for (const BoardChannel& c : spec_) {
    encodings_.push_back(channel_encoding(c.unit, c.encoding));  // refuses int32
    plants_.emplace_back(c.plant, c.initial);
    targets_.push_back(c.initial);
  }
}

void ModbusActuatorBoard::step_locked(std::int64_t now_ns) {
  for (auto& p : plants_) p.advance(now_ns);
  // The watchdog only guards motion: it trips while enabled, and latches.
  if (enabled_ && fault_ == FaultCode::kNone &&
      now_ns - last_heartbeat_ns_ > static_cast<std::int64_t>(watchdog_ms_) * 1'000'000) {
    fault_ = FaultCode::kWatchdog;
  }
  if (fault_ != FaultCode::kNone && enabled_) {
    enabled_ = false;
    for (auto& p : plants_) p.set_enabled(false);
  }
}

void ModbusActuatorBoard::apply_holding(std::int64_t now_ns, std::span<const std::uint16_t> hr,
                                        bool targets_written) {
  std::lock_guard lock(mutex_);
  step_locked(now_ns);
  if (hr[kHrWatchdogMs] != 0) watchdog_ms_ = hr[kHrWatchdogMs];
  const std::uint16_t control = hr[kHrControl];
  if ((control & kControlFaultReset) != 0) fault_ = FaultCode::kNone;
  const bool want = (control & kControlEnable) != 0 && fault_ == FaultCode::kNone;
  if (want && !enabled_) last_heartbeat_ns_ = now_ns;
  enabled_ = want;
  for (auto& p : plants_) p.set_enabled(enabled_);
  if (hr[kHrHeartbeat] != heartbeat_) {
    heartbeat_ = hr[kHrHeartbeat];
    last_heartbeat_ns_ = now_ns;
  }
  if (!targets_written) return;
  if (!enabled_) {
    target_writes_disabled_.fetch_add(1);
    return;
  }
  target_writes_.fetch_add(1);
  last_target_write_ns_.store(now_ns);
  for (std::size_t ch = 0; ch < plants_.size(); ++ch) {
    targets_[ch] = encodings_[ch].decode_u16(hr[static_cast<std::size_t>(kHrTarget0) + ch]);
    plants_[ch].command(now_ns, targets_[ch]);
  }
}

void ModbusActuatorBoard::fill_inputs(std::int64_t now_ns, std::span<std::uint16_t> ir) {
  std::lock_guard lock(mutex_);
  step_locked(now_ns);
  std::uint16_t status = enabled_ ? kStatusEnabled : 0;
  if (fault_ != FaultCode::kNone) status |= kStatusFault;
  if (fault_ == FaultCode::kWatchdog) status |= kStatusWatchdog;
  ir[kIrStatus] = status;
  ir[kIrFaultCode] = static_cast<std::uint16_t>(fault_);
  ir[kIrHeartbeatEcho] = heartbeat_;
  ir[kIrChannels] = static_cast<std::uint16_t>(plants_.size());
  for (std::size_t ch = 0; ch < plants_.size(); ++ch) {
    ir[static_cast<std::size_t>(kIrPosition0) + ch] =
        encodings_[ch].encode_u16(plants_[ch].measured());
  }
}

void ModbusActuatorBoard::advance(std::int64_t now_ns) {
  std::lock_guard lock(mutex_);
  step_locked(now_ns);
}

void ModbusActuatorBoard::inject_fault(FaultCode code) {
  std::lock_guard lock(mutex_);
  fault_ = code;
}

double ModbusActuatorBoard::position(std::size_t channel) const {
  std::lock_guard lock(mutex_);
  return plants_.at(channel).position();
}

double ModbusActuatorBoard::target(std::size_t channel) const {
  std::lock_guard lock(mutex_);
  return targets_.at(channel);
}

bool ModbusActuatorBoard::enabled() const {
  std::lock_guard lock(mutex_);
  return enabled_;
}

bool ModbusActuatorBoard::watchdog_tripped() const {
  std::lock_guard lock(mutex_);
  return fault_ == FaultCode::kWatchdog;
}

}  // namespace facectl::sim
