#include "firmware-host/model/bus_budget_check.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

#include "drivers/protocol/dynamixel2_packet.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"
#include "drivers/protocol/feetech_packet.hpp"
#include "drivers/protocol/feetech_table.hpp"
#include "drivers/protocol/maestro_serial.hpp"
#include "drivers/protocol/modbus_register_map.hpp"
#include "drivers/protocol/modbus_rtu_wire.hpp"
#include "drivers/protocol/pca9685_registers.hpp"
#include "drivers/protocol/pca9685_wire.hpp"
#include "drivers/serial/serial_port.hpp"

namespace facectl {
namespace {

std::string address_range_error(const ActuatorConfig& a, const BusConfig& bus, int max) {
  return a.where + ": rig.actuators '" + a.model.name + "'.address: expected 1.." +
         std::to_string(max) + " on " + bus.can_protocol + " bus " + bus.name + ", found " +
         std::to_string(a.model.address);
}

BusBudgetResult budget_can(const BusConfig& bus, const std::vector<const ActuatorConfig*>& acts,
                           double tick_hz) {
  BusBudgetResult r;
  std::vector<int> addresses;
  if (bus.can_protocol == "cia402") {
    for (const ActuatorConfig* a : acts) {
      if (a->model.address < 1 || a->model.address > 127) {
        throw ConfigError(address_range_error(*a, bus, 127));
      }
    }
    r.can = cia402_budget(acts.size(), bus.can, tick_hz, bus.bitrate);
  } else {
    const int per_frame = custom_can::channels_per_frame(bus.can.fd, bus.can.width);
    for (const ActuatorConfig* a : acts) {
      if (a->model.address < 1 || (a->model.address - 1) / per_frame + 1 > 63) {
        throw ConfigError(address_range_error(*a, bus, 63 * per_frame));
      }
      addresses.push_back(a->model.address);
    }
    r.can = custom_can_budget(addresses, bus.can, tick_hz, bus.bitrate);
  }
  r.load = r.can.load;
  r.text = r.can.describe(bus.name);
  r.verdict = r.can.refused()  ? BusBudgetResult::Verdict::kRefused
              : r.can.warned() ? BusBudgetResult::Verdict::kWarning
                               : BusBudgetResult::Verdict::kOk;
  return r;
}

BusBudgetResult budget_modbus(const BusConfig& bus,
                              const std::vector<const ActuatorConfig*>& acts) {
  BusBudgetResult r;
  std::vector<int> addresses;
  for (const ActuatorConfig* a : acts) {
    if (a->model.address < 1 || a->model.address > 247 * modbus_map::kChannelsPerBoard) {
      throw ConfigError(address_range_error(*a, bus, 247 * modbus_map::kChannelsPerBoard));
    }
    addresses.push_back(a->model.address);
  }
  const std::map<int, int> channels = modbus_map::board_channels(addresses);
  char buf[240];
  if (bus.type != "modbus_rtu") {
    std::snprintf(buf, sizeof buf, "%s: %zu boards over TCP (not budgeted)", bus.name.c_str(),
                  channels.size());
    r.text = buf;
    return r;
  }
  double chars = 0.0;
  for (const auto& [unit, n] : channels) chars += modbus_rtu::BoardCycleChars(n).total();
  const double wire_s = modbus_rtu::chars_to_seconds(chars, bus.bitrate);
  const double period_s = bus.modbus.cycle_period_s;
  r.load = wire_s / period_s;
  r.verdict = r.load > 1.0 ? BusBudgetResult::Verdict::kWarning : BusBudgetResult::Verdict::kOk;
  std::snprintf(buf, sizeof buf,
                "%s: %zu boards, %.0f characters per I/O cycle = %.2f ms at %ld baud, %.0f%% of "
                "the %g ms cycle%s",
                bus.name.c_str(), channels.size(), chars, wire_s * 1e3, bus.bitrate, 100.0 * r.load,
                period_s * 1e3,
                r.load > 1.0 ? " (warning: the I/O cycle cannot keep its period)" : "");
  r.text = buf;
  return r;
}

// The verdict and the line of a serial bus's budget: `wire_s` of bytes per
// I/O cycle against its period, refused when `refused` (with `refusal`).
BusBudgetResult serial_budget(const BusConfig& bus, std::size_t count, const char* units,
                              double bytes, double wire_s, double cycle_period_s, bool refused,
                              const char* refusal) {
  BusBudgetResult r;
  r.load = wire_s / cycle_period_s;
  r.verdict = refused        ? BusBudgetResult::Verdict::kRefused
              : r.load > 1.0 ? BusBudgetResult::Verdict::kWarning
                             : BusBudgetResult::Verdict::kOk;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%s: %zu %s, %.0f bytes per I/O cycle = %.2f ms at %ld baud, %.0f%% of the %g ms "
                "cycle%s",
                bus.name.c_str(), count, units, bytes, wire_s * 1e3, bus.bitrate, 100.0 * r.load,
                cycle_period_s * 1e3,
                refused        ? refusal
                : r.load > 1.0 ? " (warning: the I/O cycle cannot keep its period)"
                               : "");
  r.text = buf;
  return r;
}

BusBudgetResult budget_dynamixel(const BusConfig& bus,
                                 const std::vector<const ActuatorConfig*>& acts) {
  for (const ActuatorConfig* a : acts) {
    if (a->model.address < 0 || a->model.address > dxl2::kMaxId) {
      throw ConfigError(a->where + ": rig.actuators '" + a->model.name +
                        "'.address: expected a servo ID 0.." + std::to_string(dxl2::kMaxId) +
                        " on DYNAMIXEL bus " + bus.name + ", found " +
                        std::to_string(a->model.address));
    }
  }
  const DynamixelOptions& o = bus.dynamixel;
  const double bytes = static_cast<double>(dxl_x::cycle_bytes(acts.size()));
  const double wire_s = bytes * serial_byte_s(bus.bitrate) +
                        static_cast<double>(acts.size()) * o.return_delay_us * 1e-6;
  // A cycle that outlasts half the servos' Bus Watchdog, or the silence that
  // makes a FAULT, would stop the servos or fault the bus by itself.
  const double limit_ms = o.bus_watchdog_ms > 0
                              ? std::min(0.5 * o.bus_watchdog_ms, o.fault_after_s * 1e3)
                              : o.fault_after_s * 1e3;
  return serial_budget(bus, acts.size(), "servos", bytes, wire_s, o.cycle_period_s,
                       wire_s * 1e3 >= limit_ms,
                       " (refused: not under half watchdog_ms and under fault_after_ms; a "
                       "faster baud or fewer servos)");
}

// Maestro: the bytes of one I/O cycle (every target, a Get Position per
// channel, Get Errors and their replies) against the cycle.
BusBudgetResult budget_maestro(const BusConfig& bus,
                               const std::vector<const ActuatorConfig*>& acts) {
  for (const ActuatorConfig* a : acts) {
    if (a->model.address < 0 || a->model.address >= maestro::kMaxChannels) {
      throw ConfigError(a->where + ": rig.actuators '" + a->model.name +
                        "'.address: expected a channel 0.." +
                        std::to_string(maestro::kMaxChannels - 1) + " on Maestro bus " + bus.name +
                        ", found " + std::to_string(a->model.address));
    }
  }
  const MaestroOptions& o = bus.maestro;
  int lo = maestro::kMaxChannels, hi = -1;
  for (const ActuatorConfig* a : acts) {
    lo = std::min(lo, a->model.address);
    hi = std::max(hi, a->model.address);
  }
  const std::size_t span = hi < lo ? 0 : static_cast<std::size_t>(hi - lo + 1);
  const double bytes =
      static_cast<double>(maestro::cycle_bytes(o.protocol, acts.size(), o.multiple_targets, span));
  const double wire_s = bytes * serial_byte_s(bus.bitrate);
  // A cycle that outlasts the silence that makes a FAULT faults the bus by itself.
  return serial_budget(bus, acts.size(), "Maestro channels", bytes, wire_s, o.cycle_period_s,
                       wire_s >= o.fault_after_s,
                       " (refused: not under fault_after_ms; a faster baud or fewer channels)");
}

// Feetech: the bytes of one I/O cycle (ft::cycle_bytes) and each servo's
// return delay against the cycle; a cycle at or beyond fault_after_ms would
// fault the bus by itself.
BusBudgetResult budget_feetech(const BusConfig& bus,
                               const std::vector<const ActuatorConfig*>& acts) {
  for (const ActuatorConfig* a : acts) {
    if (a->model.address < 0 || a->model.address > scs::kMaxId) {
      throw ConfigError(a->where + ": rig.actuators '" + a->model.name +
                        "'.address: expected a servo ID 0.." + std::to_string(scs::kMaxId) +
                        " on Feetech bus " + bus.name + ", found " +
                        std::to_string(a->model.address));
    }
  }
  const FeetechOptions& o = bus.feetech;
  const double bytes = static_cast<double>(ft::cycle_bytes(o.series, acts.size()));
  const double wire_s = bytes * serial_byte_s(bus.bitrate) +
                        static_cast<double>(acts.size()) * o.return_delay_us * 1e-6;
  return serial_budget(bus, acts.size(), "servos", bytes, wire_s, o.cycle_period_s,
                       wire_s >= o.fault_after_s,
                       " (refused: not under fault_after_ms; a faster baud or fewer servos)");
}

// PCA9685: the I2C clocks of one I/O cycle (pca9685_cycle_bits) against the
// cycle, one PWM period unless cycle_ms says otherwise.
BusBudgetResult budget_pca9685(const BusConfig& bus,
                               const std::vector<const ActuatorConfig*>& acts) {
  BusBudgetResult r;
  const int boards = static_cast<int>(bus.pca9685.boards.size());
  std::vector<int> addresses;
  for (const ActuatorConfig* a : acts) {
    if (a->model.address < 1 || a->model.address > pca9685::kChannels * boards) {
      throw ConfigError(a->where + ": rig.actuators '" + a->model.name + "'.address: expected 1.." +
                        std::to_string(pca9685::kChannels * boards) + " on PCA9685 bus " +
                        bus.name + " (16 channels per listed board), found " +
                        std::to_string(a->model.address));
    }
    addresses.push_back(a->model.address);
  }
  const double clocks = pca9685_cycle_bits(addresses, boards).total;
  const double wire_s = clocks / static_cast<double>(bus.pca9685.i2c_hz);
  const double hz = pca9685::frequency_of(pca9685::prescale_for(bus.pca9685.pwm_hz));
  const double period_s = pca9685_cycle_period_s(bus.pca9685);
  r.load = wire_s / period_s;
  r.verdict = r.load > 1.0 ? BusBudgetResult::Verdict::kWarning : BusBudgetResult::Verdict::kOk;
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "%s: %d PCA9685 boards, %.0f I2C clocks per I/O cycle = %.2f ms at %ld kHz, "
                "%.0f%% of the %.3g ms cycle (PWM %.2f Hz)%s",
                bus.name.c_str(), boards, clocks, wire_s * 1e3, bus.pca9685.i2c_hz / 1000,
                100.0 * r.load, period_s * 1e3, hz,
                r.load > 1.0 ? " (warning: the I/O cycle cannot keep its period)" : "");
  r.text = buf;
  return r;
}

}  // namespace

std::vector<BusBudgetResult> check_bus_budgets(const RigConfig& rig, double tick_hz) {
  std::vector<BusBudgetResult> out;
  for (const BusConfig& bus : rig.buses) {
    std::vector<const ActuatorConfig*> acts;
    for (const ActuatorConfig& a : rig.actuators) {
      if (a.model.bus == bus.name) acts.push_back(&a);
    }
    BusBudgetResult r = bus.is_can()         ? budget_can(bus, acts, tick_hz)
                        : bus.is_dynamixel() ? budget_dynamixel(bus, acts)
                        : bus.is_feetech()   ? budget_feetech(bus, acts)
                        : bus.is_pca9685()   ? budget_pca9685(bus, acts)
                        : bus.is_maestro()   ? budget_maestro(bus, acts)
                                             : budget_modbus(bus, acts);
    r.bus = bus.name;
    r.where = bus.where;
    out.push_back(std::move(r));
  }
  return out;
}

void enforce_bus_budgets(const std::vector<BusBudgetResult>& results,
                         std::vector<std::string>& warnings) {
  for (const BusBudgetResult& r : results) {
    if (r.verdict == BusBudgetResult::Verdict::kRefused) {
      throw ConfigError(r.where + ": rig.buses '" + r.bus +
                        "': expected a bus load of at most 70%, found " + r.text +
                        "; raise rate_divider, use protocol: custom (several actuators per "
                        "frame) or fd: true, or split the bus");
    }
    if (r.verdict == BusBudgetResult::Verdict::kWarning) warnings.push_back("warning: " + r.text);
  }
}

}  // namespace facectl
