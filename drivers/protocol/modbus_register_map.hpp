#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "drivers/protocol/wire_encoding.hpp"

// The register map of facectl's Modbus actuator board (docs/PROTOCOLS.md,
// "Modbus actuator board"). Pure encode/decode: shared by the ModbusBus driver
// and the simulated board, so both sides speak exactly the documented layout.
namespace facectl::modbus_map {

inline constexpr int kChannelsPerBoard = 8;

// Holding registers (function 0x10 write, 0x03 read).
inline constexpr int kHrControl = 0;      // bit 0 enable outputs, bit 1 fault reset
inline constexpr int kHrHeartbeat = 1;    // host command counter; must change within the watchdog
inline constexpr int kHrTarget0 = 2;      // raw target of channel 0..7
inline constexpr int kHrWatchdogMs = 10;  // board watchdog, 1..65535 ms, written on connect
inline constexpr int kHoldingCount = 11;

// Input registers (function 0x04).
inline constexpr int kIrStatus = 0;         // bit 0 enabled, bit 1 fault, bit 2 watchdog tripped
inline constexpr int kIrFaultCode = 1;      // FaultCode
inline constexpr int kIrHeartbeatEcho = 2;  // last heartbeat the board accepted
inline constexpr int kIrChannels = 3;       // channels fitted on this board
inline constexpr int kIrPosition0 = 4;      // raw measured position of channel 0..7
inline constexpr int kInputCount = 12;

inline constexpr std::uint16_t kControlEnable = 0x0001;
inline constexpr std::uint16_t kControlFaultReset = 0x0002;
inline constexpr std::uint16_t kStatusEnabled = 0x0001;
inline constexpr std::uint16_t kStatusFault = 0x0002;
inline constexpr std::uint16_t kStatusWatchdog = 0x0004;

enum class FaultCode : std::uint16_t {
  kNone = 0,
  kWatchdog = 1,         // heartbeat did not change within kHrWatchdogMs while enabled
  kOverTemperature = 2,  // reported by the board's driver stage
  kPositionError = 3,    // following error beyond the board's limit
};

// Where a board's blocks sit, for boards whose register map starts elsewhere
// (rig keys enable_register, watchdog_register, status_register). The
// CONTROL, HEARTBEAT, TARGET block is contiguous from `control` (one write
// per cycle needs that); STATUS .. POSITION is contiguous from `status`.
struct Addresses {
  int control = kHrControl;
  int watchdog = kHrWatchdogMs;
  int status = kIrStatus;
};

enum class Unit { kRotary, kLinear };

// Target and position registers carry each actuator's encoding (one
// register per channel, so raw int16 or uint16): WireEncoding::encode_u16 and
// decode_u16. Throws std::invalid_argument for raw int32, which needs two
// registers the map does not have (the rig loader refuses it first).
WireEncoding channel_encoding(Unit unit, const ActuatorEncoding& encoding);
// The default encoding: 0.01 degree (rotary) or 0.01 mm (linear) per count,
// two's-complement int16, saturating at ±32767 counts (±327.67 deg or mm).
std::uint16_t to_register(Unit unit, double si);
double from_register(Unit unit, std::uint16_t reg);

// Where an actuator sits: board (Modbus unit id) and channel. The rig's
// `address` numbers channels across boards: unit = (address-1)/8 + 1,
// channel = (address-1) % 8.
struct Placement {
  int unit = 0;
  int channel = 0;
};
// Throws std::invalid_argument naming the address when it is not 1..1976
// (unit ids 1..247).
Placement place(int address);
// The boards the addresses use, in unit order: unit -> highest used channel + 1.
std::map<int, int> board_channels(std::span<const int> addresses);

}  // namespace facectl::modbus_map
