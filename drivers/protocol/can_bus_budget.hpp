#pragma once

#include <cstddef>
#include <map>
#include <span>
#include <string>

#include "drivers/can/can_bus_options.hpp"

namespace facectl {

// The load a cyclic CAN schedule puts on the bus, with 135 bits as the worst
// case for a classic 8-byte frame (111 bits nominal; stuffing and interframe
// space included). Every classic frame is budgeted at the
// worst case, whatever its length; a CAN FD frame at its own worst case
// (can_fd_frame_bits), its data phase counted at the data bitrate.
struct CanBusBudget {
  int frames_per_cycle = 0;
  double bits_per_cycle = 0.0;  // bit times at the nominal bitrate
  double cycle_hz = 0.0;
  long bitrate = 0;
  double load = 0.0;  // fraction of the bitrate

  static constexpr double kBitsPerFrame = 135.0;
  static constexpr double kWarnLoad = 0.50;
  static constexpr double kRefuseLoad = 0.70;

  // Classic frames, each at kBitsPerFrame.
  static CanBusBudget compute(int frames_per_cycle, double cycle_hz, long bitrate);
  // Frames whose worst-case length in nominal bit times adds up to `bits_per_cycle`.
  static CanBusBudget compute_bits(int frames_per_cycle, double bits_per_cycle, double cycle_hz,
                                   long bitrate);
  bool refused() const { return load > kRefuseLoad; }
  bool warned() const { return load > kWarnLoad; }
  // "can0: 25 frames per cycle at 250 Hz = 843750 bit/s, 84.4% of 1000000 bit/s"
  std::string describe(const std::string& bus) const;
};

// The smallest CAN FD data length that holds `bytes` (0..64): 0..8, 12, 16,
// 20, 24, 32, 48 or 64.
int can_fd_length(int bytes);

// Worst-case length of a CAN FD frame with an 11-bit id and `bytes` of data
// (padded to can_fd_length), in bit times at `bitrate`, the data phase
// running at `data_bitrate` (bit rate switch; equal rates: no switch).
// Arbitration and end of frame: 17 bits + 4 worst-case stuff bits + CRC
// delimiter, ACK, EOF and intermission (13) at the nominal rate. Data phase:
// ESI, DLC and data with a stuff bit every 4 bits at worst, the stuff count
// (4 bits + its fixed stuff bit), and the CRC (17 bits up to 16 data bytes,
// 21 above) with its fixed stuff bit every 4 bits.
double can_fd_frame_bits(int bytes, long bitrate, long data_bitrate);

// The boards of a custom-layout bus, in node order: node -> highest used
// channel + 1 (boards and channels follow from the addresses as in CustomCanBus).
std::map<int, int> custom_can_boards(std::span<const int> addresses, const CanBusOptions& options);

// Worst-case length, in nominal bit times, of one command (or feedback) frame
// of a custom board using `channels`: 135 classic, or its CAN FD length.
double custom_can_frame_bits(int channels, const CanBusOptions& options, long bitrate);

// The schedule of a custom-layout bus (docs/PROTOCOLS.md): one command and one
// feedback frame per board and bus cycle. `addresses` are its actuators'
// (boards and channels follow from them as in CustomCanBus).
CanBusBudget custom_can_budget(std::span<const int> addresses, const CanBusOptions& options,
                               double tick_hz, long bitrate);

// The schedule of a CiA 402 bus: SYNC, one RPDO and one TPDO per drive, plus
// the heartbeats (ours and the drives'), rounded up, per bus cycle.
CanBusBudget cia402_budget(std::size_t drives, const CanBusOptions& options, double tick_hz,
                           long bitrate);

}  // namespace facectl
