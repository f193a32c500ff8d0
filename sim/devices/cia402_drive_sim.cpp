#include "sim/devices/cia402_drive_sim.hpp"

#include <algorithm>
#include <cmath>

namespace facectl::sim {

using namespace cia402;

Cia402DriveSim::Cia402DriveSim(int node, ServoPlantParams plant, cia402::DriveCounts counts,
                               double initial_si, bool standard_mapping)
    : node_(node), counts_(counts), plant_(plant, initial_si) {
  pending_target_ = counts_.encode(initial_si);
  const auto n = static_cast<std::uint32_t>(node);
  rpdo_.cob = kRpdo1Base + n;
  tpdo_.cob = kTpdo1Base + n;
  rpdo_.map = {cia402::kMapControlword, cia402::kMapTargetPosition};
  tpdo_.map = {cia402::kMapStatusword, cia402::kMapPositionActual};
  if (!standard_mapping) {
    std::swap(rpdo_.map[0], rpdo_.map[1]);
    std::swap(tpdo_.map[0], tpdo_.map[1]);
  }
}

int Cia402DriveSim::Pdo::bytes() const {
  int n = 0;
  for (int i = 0; i < count; ++i)
    n += static_cast<int>(map[static_cast<std::size_t>(i)] & 0xFF) / 8;
  return n;
}

// CiA 301: the mapping may change only while the PDO is invalid, and its
// entries only while the count is 0. Returns false to abort the write.
bool Cia402DriveSim::write_pdo_object(Pdo& pdo, bool mapping, std::uint8_t sub, std::uint32_t v) {
  if (!mapping) {
    if (sub == 1)
      pdo.cob = v;
    else if (sub == 2)
      pdo.type = static_cast<int>(v & 0xFF);
    return sub == 1 || sub == 2;
  }
  if ((pdo.cob & cia402::kPdoInvalid) == 0) return false;
  if (sub == 0) {
    if (v > 8) return false;
    pdo.count = static_cast<int>(v);
    return pdo.bytes() <= 8;
  }
  if (sub > 8 || pdo.count != 0) return false;
  const std::uint32_t object = v >> 16;
  if (object != 0x6040 && object != 0x607A && object != 0x6041 && object != 0x6064) return false;
  pdo.map[sub - 1U] = v;
  return true;
}

std::uint16_t Cia402DriveSim::statusword() const {
  switch (ds_) {
    case DriveState::kSwitchOnDisabled:
      return 0x0250;
    case DriveState::kReadyToSwitchOn:
      return 0x0231;
    case DriveState::kSwitchedOn:
      return 0x0233;
    case DriveState::kOperationEnabled:
      return 0x0237;
    case DriveState::kQuickStopActive:
      return 0x0217;
    case DriveState::kFaultReactionActive:
      return 0x021F;
    case DriveState::kFault:
      return 0x0218;
    case DriveState::kNotReadyToSwitchOn:
      return 0x0200;
  }
  return 0;
}

void Cia402DriveSim::fault(std::uint16_t code, std::int64_t now_ns) {
  if (ds_ == DriveState::kFault) return;
  ds_ = DriveState::kFault;
  plant_.set_enabled(false);
  CanFrame e;
  e.id = kEmcyBase + static_cast<std::uint32_t>(node_);
  e.len = 8;
  put_u16(&e.data[0], code);
  e.data[2] = 0x01;  // error register: generic error
  emit(e, now_ns);
}

void Cia402DriveSim::apply_controlword(std::uint16_t cw) {
  const bool edge_reset = (cw & kCwFaultReset) != 0 && (controlword_ & kCwFaultReset) == 0;
  if (cw == kCwQuickStop && controlword_ != kCwQuickStop) quick_stops_.fetch_add(1);
  controlword_ = cw;
  last_cw_.store(cw);
  const bool voltage = (cw & 0x02) != 0;
  const bool quick = (cw & 0x04) != 0;  // active low: 0 = quick stop
  switch (ds_) {
    case DriveState::kFault:
      if (edge_reset) ds_ = DriveState::kSwitchOnDisabled;
      break;
    case DriveState::kSwitchOnDisabled:
      if ((cw & 0x87) == 0x06) ds_ = DriveState::kReadyToSwitchOn;
      break;
    case DriveState::kReadyToSwitchOn:
      if (!voltage || !quick)
        ds_ = DriveState::kSwitchOnDisabled;
      else if ((cw & 0x8F) == 0x0F)
        ds_ = DriveState::kOperationEnabled;
      else if ((cw & 0x8F) == 0x07)
        ds_ = DriveState::kSwitchedOn;
      break;
    case DriveState::kOperationEnabled:
      // Quick stop: it brakes and holds (quick stop option code 5/6: it stays
      // in quick stop active until disable voltage).
      if (voltage && !quick) {
        ds_ = DriveState::kQuickStopActive;
        plant_.command(0, plant_.position());
        return;
      }
      [[fallthrough]];
    case DriveState::kSwitchedOn:
      if (!voltage || !quick)
        ds_ = DriveState::kSwitchOnDisabled;
      else if ((cw & 0x8F) == 0x06)
        ds_ = DriveState::kReadyToSwitchOn;
      else if ((cw & 0x8F) == 0x07)
        ds_ = DriveState::kSwitchedOn;
      else if ((cw & 0x8F) == 0x0F)
        ds_ = DriveState::kOperationEnabled;
      break;
    case DriveState::kQuickStopActive:
      if (!voltage) ds_ = DriveState::kSwitchOnDisabled;
      break;
    default:
      break;
  }
  plant_.set_enabled(ds_ == DriveState::kOperationEnabled || ds_ == DriveState::kQuickStopActive);
}

void Cia402DriveSim::on_frame(const CanFrame& f, std::int64_t now_ns) {
  std::lock_guard lock(mutex_);
  const auto self = static_cast<std::uint32_t>(node_);
  if (f.id == kNmt && f.len == 2 && (f.data[1] == 0 || f.data[1] == node_)) {
    switch (static_cast<NmtCommand>(f.data[0])) {
      case NmtCommand::kStart:
        nmt_ = NmtState::kOperational;
        break;
      case NmtCommand::kStop:
        nmt_ = NmtState::kStopped;
        break;
      case NmtCommand::kPreOperational:
        nmt_ = NmtState::kPreOperational;
        break;
      default:
        nmt_ = NmtState::kPreOperational;
        booted_ = false;
        break;  // resets
    }
    return;
  }
  if (f.id == kHeartbeatBase + static_cast<std::uint32_t>(consumer_node_) && consumer_ms_ > 0) {
    consumer_armed_ = true;
    last_host_heartbeat_ns_ = now_ns;
    return;
  }
  if (f.id == kSdoRxBase + self && f.len == 8 && nmt_ != NmtState::kStopped) {
    const std::uint16_t index = get_u16(&f.data[1]);
    const std::uint8_t sub = f.data[3];
    const std::uint32_t v = get_u32(&f.data[4]);
    CanFrame r;
    r.id = kSdoTxBase + self;
    r.len = 8;
    r.data[1] = f.data[1];
    r.data[2] = f.data[2];
    r.data[3] = sub;
    if (f.data[0] == 0x40) {  // initiate upload (a read)
      upload(index, sub, r, now_ns);
      return;
    }
    if ((f.data[0] & 0xEF) == 0x60) {  // upload segment request, toggle in bit 4
      upload_segment(f, r, now_ns);
      return;
    }
    bool ok = (f.data[0] & 0xE3) == 0x23 &&  // expedited download, size indicated
              index != refused_index_.load();
    const std::uint32_t key = (static_cast<std::uint32_t>(index) << 8) | sub;
    switch (ok ? key : 0) {
      case 0x607D01:
        limit_min_ = static_cast<std::int32_t>(v);
        break;
      case 0x607D02:
        limit_max_ = static_cast<std::int32_t>(v);
        break;
      case 0x606000:
        mode_ = static_cast<int>(v & 0xFF);
        break;
      case 0x101700:
        heartbeat_ms_ = static_cast<int>(v & 0xFFFF);
        break;
      case 0x101601:
        consumer_node_ = static_cast<int>((v >> 16) & 0x7F);
        consumer_ms_ = static_cast<int>(v & 0xFFFF);
        break;
      case 0x607F00:  // max profile velocity: accepted; the plant has its own slew limit
      case 0x600700:  // abort connection option: this drive always faults
        break;
      default:
        // CiA 301: PDO parameters change only in pre-operational.
        if ((index == 0x1400 || index == 0x1600 || index == 0x1800 || index == 0x1A00) &&
            nmt_ == NmtState::kOperational) {
          mapping_refused_.fetch_add(1);
          r.data[0] = 0x80;
          put_u32(&r.data[4], 0x08000022);  // not in the present device state
          emit(r, now_ns);
          return;
        }
        if (index == 0x1400 || index == 0x1600) {
          ok = write_pdo_object(rpdo_, index == 0x1600, sub, v);
        } else if (index == 0x1800 || index == 0x1A00) {
          ok = write_pdo_object(tpdo_, index == 0x1A00, sub, v);
        } else {
          ok = false;
        }
        break;
    }
    if (ok) {
      r.data[0] = 0x60;
      sdo_writes_.fetch_add(1);
    } else {
      r.data[0] = 0x80;
      put_u32(&r.data[4], 0x06020000);  // object does not exist
    }
    emit(r, now_ns);
    return;
  }
  if (nmt_ != NmtState::kOperational) return;  // PDOs only when operational
  if ((rpdo_.cob & cia402::kPdoInvalid) == 0 && f.id == (rpdo_.cob & 0x7FF)) {
    if (f.len != rpdo_.bytes()) {
      bad_pdos_.fetch_add(1);
      return;
    }
    rpdos_.fetch_add(1);
    std::size_t at = 0;
    for (int i = 0; i < rpdo_.count; ++i) {
      const std::uint32_t e = rpdo_.map[static_cast<std::size_t>(i)];
      if (e >> 16 == 0x6040) apply_controlword(get_u16(&f.data[at]));
      if (e >> 16 == 0x607A) pending_target_ = static_cast<std::int32_t>(get_u32(&f.data[at]));
      at += (e & 0xFF) / 8;
    }
    return;
  }
  if (f.id == kSync && f.len == 0) {
    plant_.advance(now_ns);
    if (ds_ == DriveState::kOperationEnabled && mode_.load() == 8) {
      const std::int32_t t = std::clamp(pending_target_, limit_min_.load(), limit_max_.load());
      plant_.command(now_ns, counts_.decode(t));
    }
    if ((tpdo_.cob & cia402::kPdoInvalid) != 0 || feedback_stopped_.load()) return;
    CanFrame t;
    t.id = tpdo_.cob & 0x7FF;
    t.len = static_cast<std::uint8_t>(tpdo_.bytes());
    std::size_t at = 0;
    for (int i = 0; i < tpdo_.count; ++i) {
      const std::uint32_t e = tpdo_.map[static_cast<std::size_t>(i)];
      if (e >> 16 == 0x6041) put_u16(&t.data[at], statusword());
      if (e >> 16 == 0x6064) {
        put_u32(&t.data[at], static_cast<std::uint32_t>(counts_.encode(plant_.measured())));
      }
      at += (e & 0xFF) / 8;
    }
    emit(t, now_ns);
  }
}

void Cia402DriveSim::step(std::int64_t now_ns) {
  std::lock_guard lock(mutex_);
  plant_.advance(now_ns);
  if (!booted_) {
    booted_ = true;
    CanFrame b;
    b.id = kHeartbeatBase + static_cast<std::uint32_t>(node_);
    b.len = 1;
    b.data[0] = static_cast<std::uint8_t>(NmtState::kBootUp);
    emit(b, now_ns);
    last_heartbeat_sent_ns_ = now_ns;
  }
  if (heartbeat_ms_ > 0 &&
      now_ns - last_heartbeat_sent_ns_ >= static_cast<std::int64_t>(heartbeat_ms_) * 1'000'000) {
    CanFrame h;
    h.id = kHeartbeatBase + static_cast<std::uint32_t>(node_);
    h.len = 1;
    h.data[0] = static_cast<std::uint8_t>(nmt_);
    emit(h, now_ns);
    last_heartbeat_sent_ns_ = now_ns;
  }
  // Communication watchdog: the host's heartbeat stopped.
  if (consumer_armed_ &&
      now_ns - last_host_heartbeat_ns_ > static_cast<std::int64_t>(consumer_ms_) * 1'000'000) {
    consumer_armed_ = false;
    if (ds_ != DriveState::kSwitchOnDisabled) fault(0x8130, now_ns);  // heartbeat error
  }
  if (const std::uint16_t code = injected_.exchange(0); code != 0) fault(code, now_ns);
  if (const int s = injected_nmt_.exchange(-1); s >= 0) nmt_ = static_cast<NmtState>(s);
}

// The objects it can read: device type, statusword, mode display. Replies in
// the form set_upload_form picked (CiA 301 7.2.4.3.3).
void Cia402DriveSim::upload(std::uint16_t index, std::uint8_t sub, CanFrame& r,
                            std::int64_t now_ns) {
  std::uint32_t value = 0;
  int size = 0;
  if (index == 0x1000 && sub == 0) {
    value = 0x00020192;  // device type: CiA 402 servo
    size = 4;
  } else if (index == 0x6041 && sub == 0) {
    value = statusword();
    size = 2;
  } else if (index == 0x6061 && sub == 0) {
    value =
        static_cast<std::uint32_t>(forced_mode_.load() >= 0 ? forced_mode_.load() : mode_.load()) &
        0xFF;
    size = 1;
  } else {
    r.data[0] = 0x80;
    put_u32(&r.data[4], 0x06020000);  // object does not exist
    emit(r, now_ns);
    return;
  }
  sdo_uploads_.fetch_add(1);
  switch (upload_form_.load()) {
    case UploadForm::kSized:
      r.data[0] = static_cast<std::uint8_t>(0x43 | ((4 - size) << 2));
      put_u32(&r.data[4], value);
      break;
    case UploadForm::kUnsized:
      r.data[0] = 0x42;
      put_u32(&r.data[4], value);
      break;
    case UploadForm::kSegmented:
      r.data[0] = 0x41;
      put_u32(&r.data[4], static_cast<std::uint32_t>(size));
      put_u32(segment_data_.data(), value);
      segment_len_ = size;
      segment_toggle_ = false;
      break;
  }
  emit(r, now_ns);
}

void Cia402DriveSim::upload_segment(const CanFrame& f, CanFrame& r, std::int64_t now_ns) {
  const bool toggle = (f.data[0] & 0x10) != 0;
  r.data.fill(0);
  if (segment_len_ == 0 || toggle != segment_toggle_) {
    r.data[0] = 0x80;
    put_u32(&r.data[4], segment_len_ == 0 ? 0x05040001 : 0x05030000);
    emit(r, now_ns);
    return;
  }
  // All of it fits one segment: t as asked, n = unused of 7, c = last.
  r.data[0] = static_cast<std::uint8_t>((toggle ? 0x10 : 0) | ((7 - segment_len_) << 1) | 0x01);
  for (int i = 0; i < segment_len_; ++i) {
    r.data[1 + static_cast<std::size_t>(i)] = segment_data_[static_cast<std::size_t>(i)];
  }
  segment_len_ = 0;
  emit(r, now_ns);
}

DriveState Cia402DriveSim::state() const {
  std::lock_guard lock(mutex_);
  return ds_;
}
NmtState Cia402DriveSim::nmt() const {
  std::lock_guard lock(mutex_);
  return nmt_;
}
double Cia402DriveSim::position() const {
  std::lock_guard lock(mutex_);
  return plant_.position();
}

}  // namespace facectl::sim
