#include "firmware-host/config/bus_config.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "firmware-host/config/feetech_bus_config.hpp"

namespace facectl {
namespace {

constexpr double kTwoPi = 6.283185307179586;

void parse_can(const ConfigNode& node, BusConfig& bus) {
  bus.endpoint = node["interface"].string();
  bus.bitrate = node["bitrate"].integer();
  if (bus.bitrate <= 0 || bus.bitrate > 1'000'000) {
    node["bitrate"].fail("a CAN bitrate in (0, 1000000] bit/s");
  }
  CanBusOptions& o = bus.can;
  if (auto n = node.get("protocol")) {
    bus.can_protocol = n->string();
    if (bus.can_protocol != "custom" && bus.can_protocol != "cia402") n->fail("custom or cia402");
  }
  const bool cia402 = bus.can_protocol == "cia402";
  const auto only_for = [&](const char* key, bool allowed, const char* which) {
    if (!allowed && node.has(key)) {
      node[key].fail(
          std::string("no ") + key + " on a " + bus.can_protocol + " bus (" + which + ")",
          node[key].found());
    }
  };
  only_for("fd", !cia402, "CAN FD is for custom boards");
  only_for("data_bitrate", !cia402, "CAN FD is for custom boards");
  only_for("values", !cia402, "value width is for custom boards");
  for (const char* key :
       {"map_pdos", "host_node", "host_heartbeat_ms", "drive_heartbeat_ms", "drive_watchdog_ms",
        "sdo_timeout_ms", "enable_timeout_ms", "counts_per_rev", "counts_per_mm",
        "feedback_timeout_ms", "quick_stop_ms"}) {
    only_for(key, cia402, "CiA 402 drives only");
  }
  if (auto n = node.get("rate_divider")) o.cycle_divider = static_cast<int>(n->integer_in(1, 100));
  if (auto n = node.get("heartbeat_timeout_ms")) {
    o.heartbeat_timeout_s = n->number_in(5.0, 10'000.0) * 1e-3;
  }
  if (auto n = node.get("fd")) o.fd = n->boolean();
  if (auto n = node.get("data_bitrate")) {
    if (!o.fd) n->fail("data_bitrate only with fd: true", "fd: false");
    o.data_bitrate = n->integer_in(bus.bitrate, 8'000'000);
  }
  if (auto n = node.get("values")) {
    const std::string w = n->string();
    if (w == "int16") {
      o.width = custom_can::Width::kInt16;
    } else if (w == "int32") {
      o.width = custom_can::Width::kInt32;
    } else {
      n->fail("int16 or int32");
    }
  }
  if (auto n = node.get("map_pdos")) o.map_pdos = n->boolean();
  if (auto n = node.get("host_node")) o.host_node = static_cast<int>(n->integer_in(1, 127));
  if (auto n = node.get("host_heartbeat_ms"))
    o.host_heartbeat_ms = static_cast<int>(n->integer_in(1, 65535));
  if (auto n = node.get("drive_heartbeat_ms"))
    o.drive_heartbeat_ms = static_cast<int>(n->integer_in(1, 65535));
  if (auto n = node.get("drive_watchdog_ms"))
    o.drive_watchdog_ms = static_cast<int>(n->integer_in(1, 65535));
  if (auto n = node.get("sdo_timeout_ms")) o.sdo_timeout_s = n->number_in(1.0, 1000.0) * 1e-3;
  if (auto n = node.get("enable_timeout_ms"))
    o.enable_timeout_s = n->number_in(10.0, 10'000.0) * 1e-3;
  if (auto n = node.get("feedback_timeout_ms"))
    o.feedback_timeout_s = n->number_in(1.0, 10'000.0) * 1e-3;
  if (auto n = node.get("quick_stop_ms")) o.quick_stop_s = n->number_in(0.0, 10'000.0) * 1e-3;
  if (auto n = node.get("counts_per_rev")) o.rotary_counts_per_rad = n->positive() / kTwoPi;
  if (auto n = node.get("counts_per_mm")) o.linear_counts_per_m = n->positive() * 1e3;
  if (cia402) {
    // The drive's watchdog on our heartbeat must outlast a couple of our beats,
    // and our consumer must not call a drive lost before its next beat is due.
    if (o.drive_watchdog_ms < 2 * o.host_heartbeat_ms) {
      const ConfigNode at = node.get("drive_watchdog_ms") ? node["drive_watchdog_ms"] : node;
      at.fail("drive_watchdog_ms of at least twice host_heartbeat_ms (" +
                  std::to_string(2 * o.host_heartbeat_ms) + " ms)",
              std::to_string(o.drive_watchdog_ms) + " ms");
    }
    if (o.heartbeat_timeout_s * 1e3 < 2.0 * o.drive_heartbeat_ms) {
      const ConfigNode at = node.get("heartbeat_timeout_ms") ? node["heartbeat_timeout_ms"] : node;
      at.fail("heartbeat_timeout_ms of at least twice drive_heartbeat_ms (" +
                  std::to_string(2 * o.drive_heartbeat_ms) + " ms)",
              std::to_string(std::lround(o.heartbeat_timeout_s * 1e3)) + " ms");
    }
  }
}

void parse_modbus(const ConfigNode& node, BusConfig& bus) {
  if (bus.type == "modbus_rtu") {
    bus.endpoint = node["device"].string();
    bus.bitrate = node["baud"].integer();
    if (bus.bitrate <= 0) node["baud"].fail("a baud rate > 0");
  } else {
    bus.endpoint = node["host"].string();
    if (bus.endpoint.empty()) node["host"].fail("host or host:port", "an empty string");
  }
  ModbusTiming& t = bus.modbus;
  if (auto n = node.get("network_latency_ms")) t.network_latency_s = n->number_in(0.0, 20.0) * 1e-3;
  // libmodbus's own 500 ms default is what these keys exist to avoid.
  if (auto n = node.get("response_timeout_ms"))
    t.response_timeout_s = n->number_in(1.0, 250.0) * 1e-3;
  if (auto n = node.get("byte_timeout_ms")) t.byte_timeout_s = n->number_in(0.1, 100.0) * 1e-3;
  if (auto n = node.get("retries")) t.max_retries = static_cast<int>(n->integer_in(0, 5));
  if (auto n = node.get("fault_after_ms")) t.board_timeout_s = n->number_in(5.0, 10'000.0) * 1e-3;
  if (auto n = node.get("cycle_ms")) t.cycle_period_s = n->number_in(0.1, 100.0) * 1e-3;
  if (auto n = node.get("reconnect_ms"))
    t.reconnect_interval_s = n->number_in(1.0, 10'000.0) * 1e-3;
  if (auto n = node.get("watchdog_ms"))
    t.board_watchdog_ms = static_cast<int>(n->integer_in(1, 65535));
  modbus_map::Addresses& r = bus.modbus_registers;
  if (auto n = node.get("enable_register")) r.control = static_cast<int>(n->integer_in(0, 65525));
  if (auto n = node.get("status_register")) r.status = static_cast<int>(n->integer_in(0, 65523));
  r.watchdog = r.control + modbus_map::kHrWatchdogMs;  // the board's layout, unless told
  if (auto n = node.get("watchdog_register")) {
    r.watchdog = static_cast<int>(n->integer_in(0, 65535));
    // CONTROL, HEARTBEAT and up to 8 targets are written as one block.
    if (r.watchdog >= r.control && r.watchdog < r.control + 2 + modbus_map::kChannelsPerBoard) {
      n->fail("a register outside the enable block [" + std::to_string(r.control) + ", " +
              std::to_string(r.control + 2 + modbus_map::kChannelsPerBoard) +
              ") (CONTROL, HEARTBEAT, 8 targets)");
    }
  }
  // One silent board costs (retries + 1) response timeouts per cycle: the
  // fault must not fire before a single cycle has had its chance.
  const double worst_ms = (t.max_retries + 1) * t.response_timeout_s * 1e3;
  if (t.board_timeout_s * 1e3 <= worst_ms) {
    const ConfigNode at = node.get("fault_after_ms") ? node["fault_after_ms"] : node;
    at.fail("fault_after_ms above (retries + 1) x response_timeout_ms = " +
                std::to_string(std::lround(worst_ms)) + " ms",
            std::to_string(std::lround(t.board_timeout_s * 1e3)) + " ms");
  }
}

void parse_dynamixel(const ConfigNode& node, BusConfig& bus) {
  bus.endpoint = node["device"].string();
  bus.bitrate = node["baud"].integer();
  // The rates an X-series servo's Baud Rate (8) item can be set to.
  bool known = false;
  for (const long b :
       {9600L, 57600L, 115200L, 1'000'000L, 2'000'000L, 3'000'000L, 4'000'000L, 4'500'000L}) {
    known = known || b == bus.bitrate;
  }
  if (!known) {
    node["baud"].fail(
        "a rate a DYNAMIXEL X servo runs at: 9600, 57600, 115200, 1000000, 2000000, 3000000, "
        "4000000 or 4500000");
  }
  DynamixelOptions& o = bus.dynamixel;
  if (auto n = node.get("response_timeout_ms"))
    o.response_timeout_s = n->number_in(1.0, 100.0) * 1e-3;
  if (auto n = node.get("fault_after_ms")) o.fault_after_s = n->number_in(5.0, 10'000.0) * 1e-3;
  if (auto n = node.get("cycle_ms")) o.cycle_period_s = n->number_in(1.0, 100.0) * 1e-3;
  if (auto n = node.get("reconnect_ms"))
    o.reconnect_interval_s = n->number_in(1.0, 10'000.0) * 1e-3;
  if (auto n = node.get("return_delay_us")) {
    o.return_delay_us = static_cast<int>(n->integer_in(0, 508));
    if (o.return_delay_us % 2 != 0) n->fail("an even number of microseconds (the unit is 2 us)");
  }
  if (auto n = node.get("watchdog_ms")) {
    o.bus_watchdog_ms = static_cast<int>(n->integer_in(0, 2540));
    if (o.bus_watchdog_ms % 20 != 0) n->fail("0 (off) or a multiple of 20 ms (the servo's unit)");
  }
  if (auto n = node.get("write_position_limits")) o.write_position_limits = n->boolean();
  if (o.fault_after_s <= o.response_timeout_s) {
    const ConfigNode at = node.get("fault_after_ms") ? node["fault_after_ms"] : node;
    at.fail("fault_after_ms above response_timeout_ms (" +
                std::to_string(std::lround(o.response_timeout_s * 1e3)) + " ms)",
            std::to_string(std::lround(o.fault_after_s * 1e3)) + " ms");
  }
  // The servo stops itself when we fall silent: not before a cycle could come.
  if (o.bus_watchdog_ms != 0 && o.bus_watchdog_ms < 2.0 * o.cycle_period_s * 1e3) {
    node["watchdog_ms"].fail("0 (off) or at least twice cycle_ms (" +
                             std::to_string(std::lround(2.0 * o.cycle_period_s * 1e3)) + " ms)");
  }
}

// ---- PCA9685 PWM boards over i2c-dev (docs/CONFIG.md, "PCA9685 buses").
void parse_pca9685(const ConfigNode& node, BusConfig& bus) {
  node.expect_keys({"name", "type", "device", "boards", "pwm_hz", "i2c_khz", "cycle_ms"});
  bus.endpoint = node["device"].string();
  if (bus.endpoint.empty()) node["device"].fail("an i2c-dev device such as /dev/i2c-1", "\"\"");
  Pca9685Options& o = bus.pca9685;
  if (auto n = node.get("boards")) {
    o.boards.clear();
    for (const ConfigNode& b : n->items()) {
      const int address = static_cast<int>(b.integer_in(0x40, 0x7F));
      for (const int seen : o.boards) {
        if (seen == address) b.fail("a board address not listed before", std::to_string(address));
      }
      o.boards.push_back(address);
    }
    if (o.boards.empty()) n->fail("at least one board address (0x40..0x7F)", "an empty list");
  }
  // The data sheet's range with the internal 25 MHz oscillator.
  if (auto n = node.get("pwm_hz")) o.pwm_hz = n->number_in(24.0, 1526.0);
  if (auto n = node.get("i2c_khz")) o.i2c_hz = n->integer_in(10, 1000) * 1000;
  if (auto n = node.get("cycle_ms")) o.cycle_period_s = n->number_in(1.0, 1000.0) * 1e-3;
}

// ---- Pololu Maestro servo controllers over a serial port (docs/CONFIG.md,
// "Maestro buses").
void parse_maestro(const ConfigNode& node, BusConfig& bus) {
  node.expect_keys({"name", "type", "device", "baud", "protocol", "device_number",
                    "multiple_targets", "cycle_ms", "response_timeout_ms", "fault_after_ms",
                    "reconnect_ms"});
  bus.endpoint = node["device"].string();
  if (bus.endpoint.empty()) node["device"].fail("a serial device such as /dev/ttyACM0", "\"\"");
  // The guide (5.a): the UART runs at 300..200000 bit/s; the USB virtual port ignores it.
  bus.bitrate = node["baud"].integer_in(300, 200'000);
  MaestroOptions& o = bus.maestro;
  if (auto n = node.get("protocol")) {
    const std::string p = n->string();
    if (p == "compact") {
      o.protocol = maestro::Protocol::kCompact;
    } else if (p == "pololu") {
      o.protocol = maestro::Protocol::kPololu;
    } else {
      n->fail("compact or pololu");
    }
  }
  if (auto n = node.get("device_number")) {
    if (o.protocol != maestro::Protocol::kPololu) {
      n->fail("device_number only with protocol: pololu", "protocol: compact");
    }
    o.device_number = static_cast<int>(n->integer_in(0, 127));
  }
  if (auto n = node.get("multiple_targets")) o.multiple_targets = n->boolean();
  if (auto n = node.get("cycle_ms")) o.cycle_period_s = n->number_in(3.0, 1000.0) * 1e-3;
  if (auto n = node.get("response_timeout_ms"))
    o.response_timeout_s = n->number_in(1.0, 500.0) * 1e-3;
  if (auto n = node.get("fault_after_ms")) o.fault_after_s = n->number_in(5.0, 10'000.0) * 1e-3;
  if (auto n = node.get("reconnect_ms"))
    o.reconnect_interval_s = n->number_in(1.0, 10'000.0) * 1e-3;
  if (o.fault_after_s <= o.response_timeout_s) {
    const ConfigNode at = node.get("fault_after_ms") ? node["fault_after_ms"] : node;
    at.fail("fault_after_ms above response_timeout_ms (" +
                std::to_string(std::lround(o.response_timeout_s * 1e3)) + " ms)",
            std::to_string(std::lround(o.fault_after_s * 1e3)) + " ms");
  }
}

}  // namespace

BusConfig parse_bus_config(const ConfigNode& node) {
  BusConfig bus;
  bus.where = node.where();
  bus.name = node["name"].string();
  bus.type = node["type"].string();
  if (bus.type == "can") {
    std::vector<std::string> keys = {"name",
                                     "type",
                                     "interface",
                                     "bitrate",
                                     "protocol",
                                     "rate_divider",
                                     "fd",
                                     "data_bitrate",
                                     "values",
                                     "heartbeat_timeout_ms",
                                     "map_pdos",
                                     "host_node",
                                     "host_heartbeat_ms",
                                     "drive_heartbeat_ms",
                                     "drive_watchdog_ms",
                                     "sdo_timeout_ms",
                                     "enable_timeout_ms",
                                     "counts_per_rev",
                                     "counts_per_mm"};
    keys.insert(keys.end(), {"feedback_timeout_ms", "quick_stop_ms"});  // CiA 402 timing
    node.expect_keys(keys);
    parse_can(node, bus);
  } else if (bus.type == "modbus_rtu" || bus.type == "modbus_tcp") {
    std::vector<std::string> keys = {"name",
                                     "type",
                                     "response_timeout_ms",
                                     "retries",
                                     "fault_after_ms",
                                     "cycle_ms",
                                     "reconnect_ms",
                                     "watchdog_ms",
                                     "enable_register",
                                     "watchdog_register",
                                     "status_register"};
    if (bus.type == "modbus_rtu") {
      keys.insert(keys.end(), {"device", "baud", "byte_timeout_ms"});
    } else {
      keys.insert(keys.end(), {"host", "network_latency_ms"});
    }
    node.expect_keys(keys);
    parse_modbus(node, bus);
  } else if (bus.type == "dynamixel") {
    node.expect_keys({"name", "type", "device", "baud", "response_timeout_ms", "fault_after_ms",
                      "cycle_ms", "reconnect_ms", "return_delay_us", "watchdog_ms",
                      "write_position_limits"});
    parse_dynamixel(node, bus);
  } else if (bus.type == "feetech") {
    parse_feetech(node, bus);
  } else if (bus.type == "pca9685") {
    parse_pca9685(node, bus);
  } else if (bus.type == "maestro") {
    parse_maestro(node, bus);
  } else {
    node["type"].fail("one of: can, modbus_rtu, modbus_tcp, dynamixel, feetech, pca9685, maestro");
  }
  return bus;
}

}  // namespace facectl
