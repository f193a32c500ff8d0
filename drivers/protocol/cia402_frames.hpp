#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "drivers/protocol/can_frame.hpp"

// The CANopen (CiA 301) and CiA 402 frames facectl uses to drive
// off-the-shelf servo drives in cyclic synchronous position mode
// (docs/PROTOCOLS.md, "CAN: CiA 402 drives"). Pure encode/decode.
namespace facectl::cia402 {

// COB-IDs of the predefined connection set.
inline constexpr std::uint32_t kNmt = 0x000;
inline constexpr std::uint32_t kSync = 0x080;
inline constexpr std::uint32_t kEmcyBase = 0x080;   // + node
inline constexpr std::uint32_t kTpdo1Base = 0x180;  // + node: statusword, actual position
inline constexpr std::uint32_t kRpdo1Base = 0x200;  // + node: controlword, target position
inline constexpr std::uint32_t kSdoTxBase = 0x580;  // + node: drive -> host
inline constexpr std::uint32_t kSdoRxBase = 0x600;  // + node: host -> drive
inline constexpr std::uint32_t kHeartbeatBase = 0x700;

enum class NmtCommand : std::uint8_t {
  kStart = 0x01,
  kStop = 0x02,
  kPreOperational = 0x80,
  kResetNode = 0x81,
  kResetCommunication = 0x82,
};
enum class NmtState : std::uint8_t {
  kBootUp = 0x00,
  kStopped = 0x04,
  kOperational = 0x05,
  kPreOperational = 0x7F,
};

// Controlword commands (CiA 402 figure "state machine").
inline constexpr std::uint16_t kCwDisableVoltage = 0x0000;
inline constexpr std::uint16_t kCwQuickStop = 0x0002;  // bit 2 low: quick stop, voltage on
inline constexpr std::uint16_t kCwShutdown = 0x0006;
inline constexpr std::uint16_t kCwSwitchOn = 0x0007;
inline constexpr std::uint16_t kCwEnableOperation = 0x000F;
inline constexpr std::uint16_t kCwFaultReset = 0x0080;  // acts on the rising edge of bit 7

enum class DriveState {
  kNotReadyToSwitchOn,
  kSwitchOnDisabled,
  kReadyToSwitchOn,
  kSwitchedOn,
  kOperationEnabled,
  kQuickStopActive,
  kFaultReactionActive,
  kFault,
};
DriveState decode_statusword(std::uint16_t statusword);
const char* to_string(DriveState s);
// The controlword that moves a drive in `state` one step toward operation
// enabled (want_enabled) or toward switched-off. `previous` is the last
// controlword sent, so a fault reset gets its rising edge.
std::uint16_t next_controlword(DriveState state, bool want_enabled, std::uint16_t previous);

void encode_nmt(NmtCommand cmd, int node, CanFrame& out);  // node 0 = all nodes
void encode_sync(CanFrame& out);
void encode_rpdo1(int node, std::uint16_t controlword, std::int32_t target, CanFrame& out);

struct Tpdo1 {
  int node = 0;
  std::uint16_t statusword = 0;
  std::int32_t actual_position = 0;
};
std::optional<Tpdo1> decode_tpdo1(const CanFrame& f);

struct Emcy {
  int node = 0;
  std::uint16_t error_code = 0;  // 0x0000 = error reset / no error
  std::uint8_t error_register = 0;
};
std::optional<Emcy> decode_emcy(const CanFrame& f);

struct Heartbeat {
  int node = 0;
  NmtState state = NmtState::kBootUp;
};
std::optional<Heartbeat> decode_heartbeat(const CanFrame& f);

// SDO expedited download (write of 1, 2 or 4 bytes) and its reply.
void encode_sdo_download(int node, std::uint16_t index, std::uint8_t subindex, std::uint32_t value,
                         int size, CanFrame& out);
// SDO upload request (a read; `bus doctor` uses it: it changes nothing).
void encode_sdo_upload(int node, std::uint16_t index, std::uint8_t subindex, CanFrame& out);
// Upload segment request (ccs=3) after a segmented initiate reply; the
// toggle bit starts at 0 and alternates with each segment.
void encode_sdo_upload_segment(int node, bool toggle, CanFrame& out);

// Every reply form a CiA 301 SDO server may send (CiA 301 7.2.4.3).
enum class SdoReplyKind {
  kDownloadDone,     // 0x60: download confirmed
  kUploadExpedited,  // 0x4n, e=1: data in the frame (size indicated or not)
  kUploadSegmented,  // 0x40/0x41, e=0: data follows in segments
  kUploadSegment,    // scs=0: one segment (no index in it)
  kAbort,            // 0x80: abort code in bytes 4..7
};
struct SdoReply {
  int node = 0;
  SdoReplyKind kind = SdoReplyKind::kAbort;
  std::uint16_t index = 0;  // not in a segment
  std::uint8_t subindex = 0;
  bool ok = false;      // download confirmed, or expedited upload data
  bool upload = false;  // expedited upload: `value` holds the data
  std::uint32_t value = 0;
  std::uint32_t abort_code = 0;
  std::uint32_t size = 0;  // segmented initiate: bytes to come, if size_indicated
  bool size_indicated = false;
  bool toggle = false;  // segment
  bool last = false;    // segment: c bit, no more segments
  std::uint8_t segment_len = 0;
  std::uint8_t segment[7] = {};
};
std::optional<SdoReply> decode_sdo_reply(const CanFrame& f);

// A drive's host-side parameters, written by SDO each time it is enabled;
// or, with `check`, an object read back (upload) that must equal `value`.
struct SdoWrite {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::uint32_t value = 0;
  int size = 4;
  bool check = false;
};

// Mapping entries (CiA 301: index << 16 | subindex << 8 | bits).
inline constexpr std::uint32_t kMapControlword = 0x60400010;
inline constexpr std::uint32_t kMapTargetPosition = 0x607A0020;
inline constexpr std::uint32_t kMapStatusword = 0x60410010;
inline constexpr std::uint32_t kMapPositionActual = 0x60640020;
inline constexpr std::uint32_t kPdoInvalid = 0x80000000;  // COB-ID bit 31: PDO disabled

// The SDO writes that map RPDO1 (controlword, target position) and TPDO1
// (statusword, position actual), both synchronous on every SYNC, by the CiA
// 301 procedure: invalidate the PDO, clear its mapping count, write the
// entries, set the count, set the transmission type, validate the PDO.
std::vector<SdoWrite> pdo_mapping_sdos(int node);

}  // namespace facectl::cia402
