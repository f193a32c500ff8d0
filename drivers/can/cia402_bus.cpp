#include "drivers/can/cia402_bus.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace facectl {

namespace {

constexpr int kMaxRxPerTick = 512;  // bounds the drain even on a flooded bus

}  // namespace

Cia402Bus::Cia402Bus(std::string name, CanTransport& transport,
                     const std::vector<ActuatorModel>& actuators,
                     const std::vector<double>& initial_positions, CanBusOptions options)
    : name_(std::move(name)), transport_(transport), options_(options), health_(name_) {
  if (initial_positions.size() != actuators.size()) {
    throw std::invalid_argument("bus " + name_ + ": one initial position per actuator");
  }
  if (options_.cycle_divider < 1)
    throw std::invalid_argument("bus " + name_ + ": cycle divider < 1");
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    const ActuatorModel& a = actuators[i];
    if (a.address < 1 || a.address > 127) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name + " has address " +
                                  std::to_string(a.address) + ", a CANopen node id is 1..127");
    }
    for (const auto& d : drives_) {
      if (d->node == a.address) {
        throw std::invalid_argument("bus " + name_ + ": two actuators on node " +
                                    std::to_string(a.address) + " (" + a.name + ")");
      }
    }
    auto d = std::make_unique<Drive>();
    d->node = a.address;
    try {
      // The actuator's own encoding (raw int32), else the bus's counts.
      d->counts = cia402::drive_counts(a, options_);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("bus " + name_ + ": " + e.what());
    }
    d->position = initial_positions[i];
    const auto u32 = [](std::int32_t v) { return static_cast<std::uint32_t>(v); };
    const std::int32_t lo = d->counts.encode(a.limits.position_min);
    const std::int32_t hi = d->counts.encode(a.limits.position_max);
    const cia402::DriveCounts speed{std::fabs(d->counts.per_si), 0.0};  // counts/s, no offset
    // The drive enforces its own limits too, and stops on its own when our
    // heartbeat stops (its heartbeat consumer, CiA 301 object 0x1016).
    d->sdos = {
        {0x607D, 1, u32(std::min(lo, hi)), 4},  // a negative scale swaps the ends
        {0x607D, 2, u32(std::max(lo, hi)), 4},
        {0x607F, 0, u32(speed.encode(a.limits.max_velocity)), 4},
        {0x6060, 0, 8, 1},  // modes of operation: cyclic synchronous position
        {0x1017, 0, static_cast<std::uint32_t>(options_.drive_heartbeat_ms), 2},
        {0x1016, 1,
         (static_cast<std::uint32_t>(options_.host_node) << 16) |
             static_cast<std::uint32_t>(options_.drive_watchdog_ms),
         4},
        {0x6007, 0, 1, 2},  // abort connection option: go to fault
    };
    // First the PDO mapping the cycle relies on, unless the drives keep it.
    if (options_.map_pdos) {
      const auto mapping = cia402::pdo_mapping_sdos(d->node);
      d->sdos.insert(d->sdos.begin(), mapping.begin(), mapping.end());
    }
    const std::string who = name_ + " drive " + std::to_string(d->node);
    d->lost = who + ": heartbeat lost";
    d->emergency = who + ": emergency (EMCY)";
    d->drive_fault = who + ": left operation enabled (drive fault)";
    d->sdo_timeout = who + ": no SDO reply";
    d->sdo_aborted = who + ": SDO write aborted";
    d->stuck = who + ": did not reach operation enabled";
    d->rebooted = who + ": rebooted";
    drives_.push_back(std::move(d));
  }
}

void Cia402Bus::handle(const CanFrame& f, std::int64_t now_ns) {
  const auto node_of = [&](std::uint32_t base) -> Drive* {
    if (f.id <= base || f.id > base + 127) return nullptr;
    for (auto& d : drives_) {
      if (d->node == static_cast<int>(f.id - base)) return d.get();
    }
    return nullptr;
  };
  if (Drive* tpdo = node_of(cia402::kTpdo1Base)) {
    Drive* d = tpdo;
    const auto t = cia402::decode_tpdo1(f);
    if (!t) {
      bad_frames_.fetch_add(
          1, std::memory_order_relaxed);  // wrong length: ignore it, keep the last good values
      return;
    }
    d->statusword = t->statusword;
    d->position = d->counts.decode(t->actual_position);
    return;
  }
  if (Drive* hb = node_of(cia402::kHeartbeatBase)) {
    Drive* d = hb;
    const auto h = cia402::decode_heartbeat(f);
    if (!h) {
      bad_frames_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    if (h->state == cia402::NmtState::kBootUp && d->phase == Phase::kPdo) {
      set_first_reason(d->fault, d->rebooted);  // it lost its configuration while we drove it
    }
    d->heard = true;
    d->last_heartbeat_ns = now_ns;
    const char* lost = d->lost.c_str();
    d->fault.compare_exchange_strong(lost, nullptr, std::memory_order_acq_rel);
    return;
  }
  if (Drive* emcy = node_of(cia402::kEmcyBase)) {
    Drive* d = emcy;
    const auto e = cia402::decode_emcy(f);
    if (!e) {
      bad_frames_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    if (e->error_code != 0) {
      d->emcy = e->error_code;
      set_first_reason(d->fault, d->emergency);
    }
    return;
  }
  if (Drive* sdo = node_of(cia402::kSdoTxBase)) {
    Drive* d = sdo;
    const auto r = cia402::decode_sdo_reply(f);
    if (!r || !d->sdo_pending || d->sdo_next >= d->sdos.size()) return;
    const cia402::SdoWrite& w = d->sdos[d->sdo_next];
    if (r->index != w.index || r->subindex != w.subindex) return;  // not ours
    d->sdo_pending = false;
    if (r->ok) {
      ++d->sdo_next;
    } else {
      d->sdo_abort = r->abort_code;
      set_first_reason(d->fault, d->sdo_aborted);
    }
  }
}

void Cia402Bus::read(const TickTime& time, std::span<double> positions) {
  CanError err = CanError::kNone;
  for (int k = 0; k < kMaxRxPerTick && transport_.receive(frame_, err); ++k) {
    if (err != CanError::kNone) {
      health_.on_error(err, time.now_ns);
    } else {
      handle(frame_, time.now_ns);
    }
  }
  const auto timeout_ns = static_cast<std::int64_t>(options_.heartbeat_timeout_s * 1e9);
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = *drives_[i];
    // Heartbeat consumer: once a drive has been heard, or once we drive it.
    if ((d.heard || d.phase != Phase::kIdle) && time.now_ns - d.last_heartbeat_ns > timeout_ns) {
      set_first_reason(d.fault, d.lost);
    }
    if (i < positions.size()) positions[i] = d.position;
  }
  health_.end_cycle(time.now_ns);
}

void Cia402Bus::step_drive(Drive& d, double target, std::int64_t now_ns) {
  if (!d.wanted) {
    d.controlword = cia402::kCwDisableVoltage;
    cia402::encode_rpdo1(d.node, d.controlword, d.counts.encode(d.position), frame_);
    send(frame_);
    return;
  }
  if (d.phase == Phase::kIdle) {
    d.phase = Phase::kSdo;
    d.sdo_next = 0;
    d.sdo_pending = false;
    d.reached_enabled = false;
    d.controlword = cia402::kCwDisableVoltage;
    if (!d.heard) d.last_heartbeat_ns = now_ns;  // the consumer's clock starts now
  }
  if (d.phase == Phase::kSdo) {
    if (d.sdo_pending) {
      if (static_cast<double>(now_ns - d.sdo_sent_ns) * 1e-9 > options_.sdo_timeout_s) {
        set_first_reason(d.fault, d.sdo_timeout);
      }
      return;
    }
    if (d.sdo_next < d.sdos.size()) {
      const cia402::SdoWrite& w = d.sdos[d.sdo_next];
      cia402::encode_sdo_download(d.node, w.index, w.subindex, w.value, w.size, frame_);
      send(frame_);
      d.sdo_pending = true;
      d.sdo_sent_ns = now_ns;
      return;
    }
    d.phase = Phase::kStart;
  }
  if (d.phase == Phase::kStart) {
    cia402::encode_nmt(cia402::NmtCommand::kStart, d.node, frame_);
    send(frame_);
    d.phase = Phase::kPdo;
    d.pdo_since_ns = now_ns;
    return;
  }
  const cia402::DriveState state = cia402::decode_statusword(d.statusword);
  if (state == cia402::DriveState::kOperationEnabled) {
    d.reached_enabled = true;
  } else if (d.reached_enabled) {
    set_first_reason(d.fault, d.drive_fault);
  } else if (static_cast<double>(now_ns - d.pdo_since_ns) * 1e-9 > options_.enable_timeout_s) {
    set_first_reason(d.fault, d.stuck);
  }
  const std::uint16_t cw = cia402::next_controlword(state, true, d.controlword);
  // Until the drive is enabled, command where it is, so it cannot jump.
  const double where = state == cia402::DriveState::kOperationEnabled ? target : d.position;
  cia402::encode_rpdo1(d.node, cw, d.counts.encode(where), frame_);
  send(frame_);
  d.controlword = cw;
}

void Cia402Bus::write(const TickTime& time, std::span<const double> positions) {
  if (!enabled_) return;
  if (cycle_++ % static_cast<std::uint64_t>(options_.cycle_divider) != 0) return;
  for (std::size_t i = 0; i < drives_.size() && i < positions.size(); ++i) {
    step_drive(*drives_[i], positions[i], time.now_ns);
  }
  // SYNC after the RPDOs: the drives latch their targets on it (CSP).
  cia402::encode_sync(frame_);
  send(frame_);
  if (time.now_ns - last_host_heartbeat_ns_ >=
      static_cast<std::int64_t>(options_.host_heartbeat_ms) * 1'000'000) {
    frame_.id = cia402::kHeartbeatBase + static_cast<std::uint32_t>(options_.host_node);
    frame_.fd = false;
    frame_.len = 1;
    frame_.data[0] = static_cast<std::uint8_t>(cia402::NmtState::kOperational);
    send(frame_);
    last_host_heartbeat_ns_ = time.now_ns;
  }
}

void Cia402Bus::set_enabled(bool enabled) {
  if (enabled == enabled_) return;
  enabled_ = enabled;
  cycle_ = 0;
  for (auto& d : drives_) restart_drive(*d, enabled);
}

void Cia402Bus::restart_drive(Drive& d, bool wanted) {
  d.phase = Phase::kIdle;
  d.wanted = wanted;
  // Faults of the enabling attempt and of the drive's state machine belong
  // to that attempt; a lost heartbeat stays until the drive is heard again.
  const char* f = d.fault.load(std::memory_order_relaxed);
  if (f != d.lost.c_str()) d.fault.store(nullptr, std::memory_order_release);
}

void Cia402Bus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  const bool any = std::any_of(enabled.begin(), enabled.end(), [](auto on) { return on != 0; });
  if (!any || !enabled_) {
    set_enabled(any);
    if (!any) return;
  }
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = *drives_[i];
    const bool on = i < enabled.size() && enabled[i] != 0;
    // Switched on again: the full walk, holding its position until enabled.
    if (on && !d.wanted) restart_drive(d, true);
    d.wanted = on;
  }
}

BusStatus Cia402Bus::status() const {
  const char* device = nullptr;
  for (std::size_t i = 0; device == nullptr && i < drives_.size(); ++i) {
    device = drives_[i]->fault.load(std::memory_order_acquire);
  }
  return health_.status(device, bad_frames());
}

CanBusBudget Cia402Bus::budget(double tick_hz, long bitrate) const {
  return cia402_budget(drives_.size(), options_, tick_hz, bitrate);
}

cia402::DriveState Cia402Bus::drive_state(std::size_t actuator) const {
  return cia402::decode_statusword(drives_.at(actuator)->statusword);
}
std::uint16_t Cia402Bus::last_emcy(std::size_t actuator) const {
  return drives_.at(actuator)->emcy;
}
std::uint32_t Cia402Bus::last_sdo_abort(std::size_t actuator) const {
  return drives_.at(actuator)->sdo_abort;
}

}  // namespace facectl
