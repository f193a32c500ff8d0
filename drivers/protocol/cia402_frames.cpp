#include "drivers/protocol/cia402_frames.hpp"

namespace facectl::cia402 {

DriveState decode_statusword(std::uint16_t sw) {
  if ((sw & 0x4F) == 0x00) return DriveState::kNotReadyToSwitchOn;
  if ((sw & 0x4F) == 0x40) return DriveState::kSwitchOnDisabled;
  if ((sw & 0x6F) == 0x21) return DriveState::kReadyToSwitchOn;
  if ((sw & 0x6F) == 0x23) return DriveState::kSwitchedOn;
  if ((sw & 0x6F) == 0x27) return DriveState::kOperationEnabled;
  if ((sw & 0x6F) == 0x07) return DriveState::kQuickStopActive;
  if ((sw & 0x4F) == 0x0F) return DriveState::kFaultReactionActive;
  if ((sw & 0x4F) == 0x08) return DriveState::kFault;
  return DriveState::kNotReadyToSwitchOn;  // undefined pattern: treat as not ready
}

const char* to_string(DriveState s) {
  switch (s) {
    case DriveState::kNotReadyToSwitchOn:
      return "not ready to switch on";
    case DriveState::kSwitchOnDisabled:
      return "switch on disabled";
    case DriveState::kReadyToSwitchOn:
      return "ready to switch on";
    case DriveState::kSwitchedOn:
      return "switched on";
    case DriveState::kOperationEnabled:
      return "operation enabled";
    case DriveState::kQuickStopActive:
      return "quick stop active";
    case DriveState::kFaultReactionActive:
      return "fault reaction active";
    case DriveState::kFault:
      return "fault";
  }
  return "?";
}

std::uint16_t next_controlword(DriveState state, bool want_enabled, std::uint16_t previous) {
  if (!want_enabled) return kCwDisableVoltage;
  switch (state) {
    case DriveState::kFault:
      // Bit 7 acts on its rising edge: send 0 first if it is already high.
      return (previous & kCwFaultReset) != 0 ? kCwDisableVoltage : kCwFaultReset;
    case DriveState::kSwitchOnDisabled:
      return kCwShutdown;
    case DriveState::kReadyToSwitchOn:
      return kCwSwitchOn;
    case DriveState::kSwitchedOn:
    case DriveState::kOperationEnabled:
      return kCwEnableOperation;
    case DriveState::kQuickStopActive:
      return kCwDisableVoltage;
    case DriveState::kNotReadyToSwitchOn:
    case DriveState::kFaultReactionActive:
      return previous;  // the drive moves on its own
  }
  return kCwDisableVoltage;
}

void encode_nmt(NmtCommand cmd, int node, CanFrame& out) {
  out.id = kNmt;
  out.fd = false;
  out.len = 2;
  out.data[0] = static_cast<std::uint8_t>(cmd);
  out.data[1] = static_cast<std::uint8_t>(node);
}

void encode_sync(CanFrame& out) {
  out.id = kSync;
  out.fd = false;
  out.len = 0;
}

void encode_rpdo1(int node, std::uint16_t controlword, std::int32_t target, CanFrame& out) {
  out.id = kRpdo1Base + static_cast<std::uint32_t>(node);
  out.fd = false;
  out.len = 6;
  put_u16(&out.data[0], controlword);
  put_u32(&out.data[2], static_cast<std::uint32_t>(target));
}

std::optional<Tpdo1> decode_tpdo1(const CanFrame& f) {
  if (f.id <= kTpdo1Base || f.id > kTpdo1Base + 127 || f.len != 6) return std::nullopt;
  return Tpdo1{static_cast<int>(f.id - kTpdo1Base), get_u16(&f.data[0]),
               static_cast<std::int32_t>(get_u32(&f.data[2]))};
}

std::optional<Emcy> decode_emcy(const CanFrame& f) {
  if (f.id <= kEmcyBase || f.id > kEmcyBase + 127 || f.len != 8) return std::nullopt;
  return Emcy{static_cast<int>(f.id - kEmcyBase), get_u16(&f.data[0]), f.data[2]};
}

std::optional<Heartbeat> decode_heartbeat(const CanFrame& f) {
  if (f.id <= kHeartbeatBase || f.id > kHeartbeatBase + 127 || f.len != 1) return std::nullopt;
  return Heartbeat{static_cast<int>(f.id - kHeartbeatBase),
                   static_cast<NmtState>(f.data[0] & 0x7F)};
}

void encode_sdo_download(int node, std::uint16_t index, std::uint8_t subindex, std::uint32_t value,
                         int size, CanFrame& out) {
  out.id = kSdoRxBase + static_cast<std::uint32_t>(node);
  out.fd = false;
  out.len = 8;
  // ccs=1, expedited, size indicated, n = 4 - size unused bytes.
  out.data[0] = static_cast<std::uint8_t>(0x23 | ((4 - size) << 2));
  put_u16(&out.data[1], index);
  out.data[3] = subindex;
  put_u32(&out.data[4], size == 4 ? value : (value & ((1u << (8 * size)) - 1)));
}

void encode_sdo_upload(int node, std::uint16_t index, std::uint8_t subindex, CanFrame& out) {
  out.id = kSdoRxBase + static_cast<std::uint32_t>(node);
  out.fd = false;
  out.len = 8;
  out.data.fill(0);
  out.data[0] = 0x40;  // ccs=2: initiate upload
  put_u16(&out.data[1], index);
  out.data[3] = subindex;
}

void encode_sdo_upload_segment(int node, bool toggle, CanFrame& out) {
  out.id = kSdoRxBase + static_cast<std::uint32_t>(node);
  out.fd = false;
  out.len = 8;
  out.data.fill(0);
  out.data[0] = static_cast<std::uint8_t>(0x60 | (toggle ? 0x10 : 0x00));
}

// Command byte layouts: CiA 301 7.2.4.3.3 (initiate upload: scs=2, n, e, s),
// 7.2.4.3.5 (upload segment: scs=0, t, n, c), 7.2.4.3.2 (download: scs=3).
std::optional<SdoReply> decode_sdo_reply(const CanFrame& f) {
  if (f.id <= kSdoTxBase || f.id > kSdoTxBase + 127 || f.len != 8) return std::nullopt;
  SdoReply r;
  r.node = static_cast<int>(f.id - kSdoTxBase);
  const std::uint8_t cmd = f.data[0];
  if ((cmd & 0xE0) == 0x00) {  // scs=0: upload segment, seven data bytes at most
    r.kind = SdoReplyKind::kUploadSegment;
    r.toggle = (cmd & 0x10) != 0;
    r.last = (cmd & 0x01) != 0;
    r.segment_len = static_cast<std::uint8_t>(7 - ((cmd >> 1) & 0x7));
    for (int i = 0; i < r.segment_len; ++i) r.segment[i] = f.data[1 + static_cast<std::size_t>(i)];
    return r;
  }
  r.index = get_u16(&f.data[1]);
  r.subindex = f.data[3];
  if (cmd == 0x80) {
    r.kind = SdoReplyKind::kAbort;
    r.abort_code = get_u32(&f.data[4]);
  } else if (cmd == 0x60) {
    r.kind = SdoReplyKind::kDownloadDone;
    r.ok = true;
  } else if ((cmd & 0xF2) == 0x42) {  // scs=2, e=1: expedited
    r.kind = SdoReplyKind::kUploadExpedited;
    r.ok = true;
    r.upload = true;
    r.value = get_u32(&f.data[4]);
    const int unused = (cmd & 0x01) != 0 ? (cmd >> 2) & 0x3 : 0;  // n counts only with s=1
    if (unused > 0) r.value &= (1u << (8 * (4 - unused))) - 1;
  } else if ((cmd & 0xF2) == 0x40) {  // scs=2, e=0: segmented, size in bytes 4..7 if s=1
    r.kind = SdoReplyKind::kUploadSegmented;
    r.size_indicated = (cmd & 0x01) != 0;
    r.size = r.size_indicated ? get_u32(&f.data[4]) : 0;
  } else {
    return std::nullopt;  // not a reply to anything facectl sends
  }
  return r;
}

std::vector<SdoWrite> pdo_mapping_sdos(int node) {
  const auto n = static_cast<std::uint32_t>(node);
  std::vector<SdoWrite> out;
  const auto map = [&](std::uint16_t comm, std::uint16_t mapping, std::uint32_t cob,
                       std::uint32_t first, std::uint32_t second) {
    out.push_back({comm, 1, kPdoInvalid | (cob + n), 4});
    out.push_back({mapping, 0, 0, 1});
    out.push_back({mapping, 1, first, 4});
    out.push_back({mapping, 2, second, 4});
    out.push_back({mapping, 0, 2, 1});
    out.push_back({comm, 2, 1, 1});  // synchronous, every SYNC
    out.push_back({comm, 1, cob + n, 4});
  };
  map(0x1400, 0x1600, kRpdo1Base, kMapControlword, kMapTargetPosition);
  map(0x1800, 0x1A00, kTpdo1Base, kMapStatusword, kMapPositionActual);
  return out;
}

}  // namespace facectl::cia402
