#include "sim/devices/sim_bus_timing.hpp"

#include <map>

#include "drivers/protocol/can_bus_budget.hpp"
#include "drivers/protocol/custom_can_frames.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"
#include "drivers/protocol/modbus_register_map.hpp"
#include "drivers/protocol/modbus_rtu_wire.hpp"
#include "drivers/protocol/pca9685_wire.hpp"

namespace facectl {
namespace {

SimBusTiming can_timing(const BusSpec& bus, std::span<const int> addresses, double tick_hz) {
  SimBusTiming t;
  const double bit_s = 1.0 / static_cast<double>(bus.bitrate);
  CanBusBudget budget;
  if (bus.can_protocol == "cia402") {
    budget = cia402_budget(addresses.size(), bus.can, tick_hz, bus.bitrate);
    const double frames = static_cast<double>(addresses.size() + 1);  // RPDOs, SYNC
    const double sync_end = frames * CanBusBudget::kBitsPerFrame * bit_s;
    t.arrival_s.assign(addresses.size(), sync_end);
  } else {
    budget = custom_can_budget(addresses, bus.can, tick_hz, bus.bitrate);
    const std::map<int, int> boards = custom_can_boards(addresses, bus.can);
    std::map<int, double> lands;  // node -> end of its command frame
    double bits = 0.0;
    for (const auto& [node, used] : boards) {
      bits += custom_can_frame_bits(used, bus.can, bus.bitrate);
      lands[node] = bits * bit_s;
    }
    const int per_frame = custom_can::channels_per_frame(bus.can.fd, bus.can.width);
    for (int a : addresses) t.arrival_s.push_back(lands[(a - 1) / per_frame + 1]);
  }
  t.timing.cycle_time_s = budget.bits_per_cycle * bit_s;
  t.timing.load = budget.load;
  return t;
}

SimBusTiming rtu_timing(const BusSpec& bus, std::span<const int> addresses) {
  SimBusTiming t;
  std::map<int, double> lands;  // unit -> end of its write request
  double chars = 0.0;
  for (const auto& [unit, n] : modbus_map::board_channels(addresses)) {
    const modbus_rtu::BoardCycleChars board(n);
    lands[unit] = modbus_rtu::chars_to_seconds(chars + board.until_written(), bus.bitrate);
    chars += board.total();
  }
  for (int a : addresses) t.arrival_s.push_back(lands[modbus_map::place(a).unit]);
  t.timing.cycle_time_s = modbus_rtu::chars_to_seconds(chars, bus.bitrate);
  // The I/O thread runs one cycle per cycle period (bus_budget_check).
  t.timing.load = t.timing.cycle_time_s / bus.modbus.cycle_period_s;
  return t;
}

// One Sync Write carries every goal: they land when it ends; the cycle is
// the whole exchange (dxl_x::cycle_bytes) at the cycle period.
SimBusTiming dynamixel_timing(const BusSpec& bus, std::span<const int> addresses) {
  SimBusTiming t;
  const double byte_s = 10.0 / static_cast<double>(bus.bitrate);
  const std::size_t n = addresses.size();
  t.arrival_s.assign(n, static_cast<double>(14 + 5 * n) * byte_s);
  t.timing.cycle_time_s = static_cast<double>(dxl_x::cycle_bytes(n)) * byte_s +
                          static_cast<double>(n) * bus.dynamixel.return_delay_us * 1e-6;
  t.timing.load = t.timing.cycle_time_s / bus.dynamixel.cycle_period_s;
  return t;
}

// PCA9685: a channel's pulse changes when its board's last block write ends;
// boards are served in list order.
SimBusTiming pca9685_timing(const BusSpec& bus, std::span<const int> addresses) {
  SimBusTiming t;
  const int boards = static_cast<int>(bus.pca9685.boards.size());
  const Pca9685CycleBits bits = pca9685_cycle_bits(addresses, boards);
  const double clock_s = 1.0 / static_cast<double>(bus.pca9685.i2c_hz);
  for (int a : addresses) {
    t.arrival_s.push_back(bits.written.at(pca9685_place(a, boards).board) * clock_s);
  }
  t.timing.cycle_time_s = bits.total * clock_s;
  t.timing.load = t.timing.cycle_time_s / pca9685_cycle_period_s(bus.pca9685);
  return t;
}

}  // namespace

SimBusTiming sim_bus_timing(const BusSpec& bus, std::span<const int> addresses, double tick_hz) {
  if (bus.type == "can") return can_timing(bus, addresses, tick_hz);
  if (bus.type == "modbus_rtu") return rtu_timing(bus, addresses);
  if (bus.type == "dynamixel") return dynamixel_timing(bus, addresses);
  if (bus.type == "pca9685") return pca9685_timing(bus, addresses);
  SimBusTiming t;  // modbus_tcp: the network's latency; its load is not modelled
  t.arrival_s.assign(addresses.size(), bus.modbus.network_latency_s);
  t.timing.cycle_time_s = bus.modbus.network_latency_s;
  return t;
}

}  // namespace facectl
