#include "drivers/can/cia402_bus.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <stdexcept>

#include "drivers/protocol/sdo_abort_codes.hpp"

namespace facectl {

namespace {

constexpr std::uint32_t kModeCsp = 8;  // CiA 402 modes of operation
constexpr int kMaxRxPerTick = 512;     // bounds the drain even on a flooded bus
constexpr std::int64_t kMs = 1'000'000;
// The default TPDO timeout: ten bus cycles, at least 20 ms (docs/PROTOCOLS.md).
constexpr int kFeedbackCycles = 10;
constexpr std::int64_t kMinFeedbackTimeoutNs = 20 * kMs;

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
  if (options_.host_node < 1 || options_.host_node > 127) {
    throw std::invalid_argument("bus " + name_ + ": host node " +
                                std::to_string(options_.host_node) + ", a node id is 1..127");
  }
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    const ActuatorModel& a = actuators[i];
    if (a.address < 1 || a.address > 127) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name + " has address " +
                                  std::to_string(a.address) + ", a CANopen node id is 1..127");
    }
    if (a.address == options_.host_node) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name + " has node id " +
                                  std::to_string(a.address) +
                                  ", which is the host's own (host_node)");
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
    // Its heartbeat first, so our consumer can start early (CiA 301 0x1017;
    // drives ship with 0, no heartbeat). The drive enforces its own limits
    // too, and stops on its own when our heartbeat stops (its heartbeat
    // consumer, 0x1016). The mode is read back: 0x6061 says which mode runs.
    d->sdos = {{0x1017, 0, static_cast<std::uint32_t>(options_.drive_heartbeat_ms), 2}};
    // Then the PDO mapping the cycle relies on, unless the drives keep it.
    if (options_.map_pdos) {
      const auto mapping = cia402::pdo_mapping_sdos(d->node);
      d->sdos.insert(d->sdos.end(), mapping.begin(), mapping.end());
    }
    const std::vector<cia402::SdoWrite> rest = {
        {0x607D, 1, u32(std::min(lo, hi)), 4},  // a negative scale swaps the ends
        {0x607D, 2, u32(std::max(lo, hi)), 4},
        {0x607F, 0, u32(speed.encode(a.limits.max_velocity)), 4},
        {0x6060, 0, kModeCsp, 1},        // modes of operation: cyclic synchronous position
        {0x6061, 0, kModeCsp, 1, true},  // modes of operation display: it took it
        {0x1016, 1,
         (static_cast<std::uint32_t>(options_.host_node) << 16) |
             static_cast<std::uint32_t>(options_.drive_watchdog_ms),
         4},
        {0x6007, 0, 1, 2},  // abort connection option: go to fault
    };
    d->sdos.insert(d->sdos.end(), rest.begin(), rest.end());
    d->who = name_ + " drive " + std::to_string(d->node);
    const std::string& who = d->who;
    d->lost = who + ": heartbeat lost";
    d->emergency = who + ": emergency (EMCY)";
    d->drive_fault = who + ": left operation enabled (drive fault)";
    d->sdo_timeout = who + ": no SDO reply";
    d->stuck = who + ": did not reach operation enabled";
    d->rebooted = who + ": rebooted";
    d->preop = who + ": heartbeat reports pre-operational (NMT; a communication error?)";
    d->stopped = who + ": heartbeat reports stopped (NMT)";
    d->no_feedback = who + ": position feedback (TPDO1) stopped";
    d->wrong_reply = who + ": SDO reply of the wrong kind (upload for download or back)";
    d->bad_upload = who + ": SDO upload longer than 4 bytes or out of toggle";
    drives_.push_back(std::move(d));
  }
}

void Cia402Bus::fail_detail(Drive& d, const char* format, ...) {
  // Only while no reason stands: a reader may hold the buffer's pointer.
  if (d.fault.load(std::memory_order_relaxed) != nullptr) return;
  va_list args;
  va_start(args, format);
  std::vsnprintf(d.detail.data(), d.detail.size(), format, args);
  va_end(args);
  const char* expected = nullptr;
  d.fault.compare_exchange_strong(expected, d.detail.data(), std::memory_order_acq_rel);
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
    d->last_tpdo_ns = now_ns;
    d->tpdo_sync = syncs_;
    return;
  }
  if (Drive* hb = node_of(cia402::kHeartbeatBase)) {
    Drive* d = hb;
    const auto h = cia402::decode_heartbeat(f);
    if (!h) {
      bad_frames_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    if (h->state == cia402::NmtState::kBootUp) {
      if (d->phase == Phase::kPdo) set_first_reason(d->fault, d->rebooted);
      d->heartbeat_set = false;  // back to its default heartbeat (none, mostly)
    }
    // Started by us but no longer operational: 0x1029 took it to pre-operational
    // on a communication error, or it was stopped. A beat already on its way
    // when we sent NMT start is allowed one heartbeat period.
    const bool late = now_ns - d->pdo_since_ns > options_.drive_heartbeat_ms * kMs;
    if (d->phase == Phase::kPdo && late) {
      if (h->state == cia402::NmtState::kPreOperational) set_first_reason(d->fault, d->preop);
      if (h->state == cia402::NmtState::kStopped) set_first_reason(d->fault, d->stopped);
    }
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
    if (const auto r = cia402::decode_sdo_reply(f)) handle_sdo(*sdo, *r, now_ns);
  }
}

// One SDO transfer at a time per drive (CiA 301 7.2.4). A reply must be of
// the kind the request asks for: a download is confirmed only by 0x60, an
// upload only by its data.
void Cia402Bus::handle_sdo(Drive& d, const cia402::SdoReply& r, std::int64_t now_ns) {
  using cia402::SdoReplyKind;
  if (d.sdo == Sdo::kIdle || d.sdo_next >= d.sdos.size()) return;
  const cia402::SdoWrite& w = d.sdos[d.sdo_next];
  if (r.kind == SdoReplyKind::kUploadSegment) {
    if (d.sdo != Sdo::kSegments) return;
    if (r.toggle != d.sdo_toggle || d.sdo_bytes + r.segment_len > 4) {
      d.sdo = Sdo::kIdle;
      set_first_reason(d.fault, d.bad_upload);
      return;
    }
    for (int i = 0; i < r.segment_len; ++i) {
      d.sdo_value |= static_cast<std::uint32_t>(r.segment[i]) << (8 * d.sdo_bytes++);
    }
    if (r.last) {
      sdo_done(d, d.sdo_value, now_ns);
      return;
    }
    d.sdo_toggle = !d.sdo_toggle;
    cia402::encode_sdo_upload_segment(d.node, d.sdo_toggle, frame_);
    send(frame_);
    d.sdo_sent_ns = now_ns;
    return;
  }
  if (r.index != w.index || r.subindex != w.subindex) return;  // not ours
  if (r.kind == SdoReplyKind::kAbort) {
    d.sdo = Sdo::kIdle;
    d.sdo_abort = r.abort_code;
    fail_detail(d, "%s: SDO %s 0x%04X:%02X aborted: 0x%08X %s", d.who.c_str(),
                w.check ? "upload" : "download", w.index, w.subindex, r.abort_code,
                cia402::sdo_abort_text(r.abort_code));
    return;
  }
  const bool upload_reply = r.kind != SdoReplyKind::kDownloadDone;
  if (upload_reply != (d.sdo != Sdo::kDownload)) {
    d.sdo = Sdo::kIdle;
    set_first_reason(d.fault, d.wrong_reply);
    return;
  }
  if (r.kind == SdoReplyKind::kUploadSegmented) {
    if (d.sdo != Sdo::kUpload || (r.size_indicated && r.size > 4)) {
      d.sdo = Sdo::kIdle;
      set_first_reason(d.fault, d.bad_upload);
      return;
    }
    d.sdo = Sdo::kSegments;
    d.sdo_toggle = false;
    d.sdo_value = 0;
    d.sdo_bytes = 0;
    cia402::encode_sdo_upload_segment(d.node, false, frame_);
    send(frame_);
    d.sdo_sent_ns = now_ns;
    return;
  }
  sdo_done(d, r.value, now_ns);
}

void Cia402Bus::sdo_done(Drive& d, std::uint32_t uploaded, std::int64_t now_ns) {
  const cia402::SdoWrite& w = d.sdos[d.sdo_next];
  d.sdo = Sdo::kIdle;
  if (w.check) {
    const std::uint32_t mask = w.size >= 4 ? 0xFFFFFFFFu : (1u << (8 * w.size)) - 1;
    if ((uploaded & mask) != w.value) {
      fail_detail(
          d, "%s: 0x%04X:%02X reads %u, expected %u%s", d.who.c_str(), w.index, w.subindex,
          uploaded & mask, w.value,
          w.index == 0x6061 ? " (mode of operation: 8 is cyclic synchronous position)" : "");
      return;
    }
  }
  if (w.index == 0x1017 && !w.check) {
    // It beats from now on: the consumer starts here, not before.
    d.heartbeat_set = true;
    d.last_heartbeat_ns = now_ns;
  }
  ++d.sdo_next;
}

void Cia402Bus::read(const TickTime& time, std::span<double> positions) {
  now_ns_ = time.now_ns;
  CanError err = CanError::kNone;
  for (int k = 0; k < kMaxRxPerTick && transport_.receive(frame_, err); ++k) {
    if (err != CanError::kNone) {
      health_.on_error(err, time.now_ns);
    } else {
      handle(frame_, time.now_ns);
    }
  }
  if (options_.feedback_timeout_s > 0.0) {
    feedback_timeout_ns_ = static_cast<std::int64_t>(options_.feedback_timeout_s * 1e9);
  } else {
    const auto cycles_ns =
        static_cast<std::int64_t>(kFeedbackCycles * options_.cycle_divider * time.dt_s * 1e9);
    feedback_timeout_ns_ = std::max(cycles_ns, kMinFeedbackTimeoutNs);
  }
  const auto timeout_ns = static_cast<std::int64_t>(options_.heartbeat_timeout_s * 1e9);
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = *drives_[i];
    // Heartbeat consumer: from the moment the drive confirmed its 0x1017.
    if (d.heartbeat_set && time.now_ns - d.last_heartbeat_ns > timeout_ns) {
      set_first_reason(d.fault, d.lost);
    }
    // Its TPDO1 stopped while we drive it but its heartbeat goes on: one
    // came after the last TPDO. A drive silent altogether is the heartbeat
    // consumer's to name. Counting our SYNCs too keeps a stall of our own
    // loop (no SYNC, so no TPDO) from being blamed on the drive.
    if (d.phase == Phase::kPdo && d.last_heartbeat_ns > d.last_tpdo_ns &&
        syncs_ - d.tpdo_sync > static_cast<std::uint64_t>(kFeedbackCycles) &&
        time.now_ns - d.last_tpdo_ns > feedback_timeout_ns_) {
      set_first_reason(d.fault, d.no_feedback);
    }
    if (i < positions.size()) positions[i] = d.position;
  }
  if (stopping_ && cycle_++ % static_cast<std::uint64_t>(options_.cycle_divider) == 0) {
    stop_cycle(time.now_ns);
  }
  health_.end_cycle(time.now_ns);
}

// Switched off: quick stop (the drive brakes on its own quick stop ramp,
// CiA 402 0x605A) until it reports switch on disabled or quick_stop_s has
// passed, then disable voltage (torque off), held while the bus runs.
void Cia402Bus::stop_drive(Drive& d, std::int64_t now_ns) {
  if (d.stop_since_ns < 0) d.stop_since_ns = now_ns;
  const cia402::DriveState state = cia402::decode_statusword(d.statusword);
  const bool braking = d.phase == Phase::kPdo && !d.stop_done &&
                       state != cia402::DriveState::kSwitchOnDisabled &&
                       state != cia402::DriveState::kFault &&
                       static_cast<double>(now_ns - d.stop_since_ns) * 1e-9 < options_.quick_stop_s;
  d.controlword = braking ? cia402::kCwQuickStop : cia402::kCwDisableVoltage;
  d.stop_done = !braking;
  cia402::encode_rpdo1(d.node, d.controlword, d.counts.encode(d.position), frame_);
  send(frame_);
}

void Cia402Bus::step_drive(Drive& d, double target, std::int64_t now_ns) {
  if (!d.wanted) {
    stop_drive(d, now_ns);
    return;
  }
  if (d.phase == Phase::kIdle) {
    d.sdo_next = 0;
    d.sdo = Sdo::kIdle;
    d.reached_enabled = false;
    d.controlword = cia402::kCwDisableVoltage;
    d.phase = options_.map_pdos ? Phase::kPreOp : Phase::kSdo;
  }
  if (d.phase == Phase::kPreOp) {
    // CiA 301: PDO mapping changes only in pre-operational (its PDOs stop).
    cia402::encode_nmt(cia402::NmtCommand::kPreOperational, d.node, frame_);
    send(frame_);
    d.phase = Phase::kSdo;
    return;
  }
  if (d.phase == Phase::kSdo) {
    if (d.sdo != Sdo::kIdle) {
      if (static_cast<double>(now_ns - d.sdo_sent_ns) * 1e-9 > options_.sdo_timeout_s) {
        set_first_reason(d.fault, d.sdo_timeout);
      }
      return;
    }
    if (d.fault.load(std::memory_order_relaxed) != nullptr) return;  // an abort: stay there
    if (d.sdo_next < d.sdos.size()) {
      const cia402::SdoWrite& w = d.sdos[d.sdo_next];
      if (w.check) {
        cia402::encode_sdo_upload(d.node, w.index, w.subindex, frame_);
      } else {
        cia402::encode_sdo_download(d.node, w.index, w.subindex, w.value, w.size, frame_);
      }
      send(frame_);
      d.sdo = w.check ? Sdo::kUpload : Sdo::kDownload;
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
    d.last_tpdo_ns = now_ns;  // the feedback timeout runs from here
    d.tpdo_sync = syncs_;
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

void Cia402Bus::end_of_cycle(std::int64_t now_ns) {
  // SYNC after the RPDOs: the drives latch their targets on it (CSP).
  cia402::encode_sync(frame_);
  send(frame_);
  ++syncs_;
  if (now_ns - last_host_heartbeat_ns_ >= options_.host_heartbeat_ms * kMs) {
    frame_.id = cia402::kHeartbeatBase + static_cast<std::uint32_t>(options_.host_node);
    frame_.fd = false;
    frame_.len = 1;
    frame_.data[0] = static_cast<std::uint8_t>(cia402::NmtState::kOperational);
    send(frame_);
    last_host_heartbeat_ns_ = now_ns;
  }
}

void Cia402Bus::write(const TickTime& time, std::span<const double> positions) {
  if (!enabled_) return;
  if (cycle_++ % static_cast<std::uint64_t>(options_.cycle_divider) != 0) return;
  for (std::size_t i = 0; i < drives_.size() && i < positions.size(); ++i) {
    step_drive(*drives_[i], positions[i], time.now_ns);
  }
  end_of_cycle(time.now_ns);
}

// The bus is off: only read() runs. Each drive that was operational gets
// its stop sequence; once every one has had disable voltage, silence.
void Cia402Bus::stop_cycle(std::int64_t now_ns) {
  bool done = true, any = false;
  for (auto& d : drives_) {
    if (d->phase != Phase::kPdo || d->stop_done) continue;
    stop_drive(*d, now_ns);
    any = true;
    done = done && d->stop_done;
  }
  if (any) end_of_cycle(now_ns);
  if (!done) return;
  stopping_ = false;
  for (auto& d : drives_) d->phase = Phase::kIdle;
}

void Cia402Bus::set_enabled(bool enabled) {
  if (enabled == enabled_) return;
  enabled_ = enabled;
  cycle_ = 0;
  for (auto& d : drives_) {
    const bool was_operational = d->phase == Phase::kPdo;
    restart_drive(*d, enabled);
    // Disabled: drives we ran keep their phase until stop_cycle is through.
    if (!enabled && was_operational) d->phase = Phase::kPdo;
  }
  stopping_ = !enabled;
  if (stopping_) stop_cycle(now_ns_);  // quick stop goes out on this tick
}

void Cia402Bus::restart_drive(Drive& d, bool wanted) {
  d.phase = Phase::kIdle;
  d.wanted = wanted;
  d.stop_since_ns = -1;
  d.stop_done = false;
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
    // Switched off: its stop sequence starts on the next cycle.
    if (!on && d.wanted) {
      d.stop_since_ns = -1;
      d.stop_done = false;
    }
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
