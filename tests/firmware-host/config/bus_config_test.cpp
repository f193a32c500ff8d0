// Rig bus keys, actuator encodings against their bus, the runtime file's
// hardware, safety_io and gamepad blocks, and the bus budget at config load:
// what they accept, and errors that name file:line:col, the key, what was
// expected and what was found.
#include <gtest/gtest.h>

#include "drivers/protocol/can_bus_budget.hpp"
#include "drivers/protocol/feetech_table.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "firmware-host/config/runtime_config.hpp"
#include "firmware-host/model/bus_budget_check.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

using testing::TempFile;

const HeadConfig& head() {
  static const HeadConfig h =
      load_head_config(std::string(FACECTL_SOURCE_DIR) + "/config/heads/default/head.yaml");
  return h;
}

// A rig with one bus (`bus` is its flow mapping's inner keys) and `count`
// rotary actuators on it, addresses 1..count.
std::string rig(const std::string& bus, int count = 1) {
  std::string s = "rig:\n  name: t\n  buses:\n    - { name: b0, " + bus + " }\n  actuators:\n";
  for (int i = 1; i <= count; ++i) {
    s += "    - { name: a" + std::to_string(i) +
         ", kind: rotary, bus: b0, address: " + std::to_string(i) +
         ", position_deg: { min: -6, max: 20 }, max_velocity_deg_s: 100, "
         "max_acceleration_deg_s2: 1000, rest_deg: 0, map: { terms: { jaw_pitch_deg: 1 } } }\n";
  }
  return s;
}

const std::string kCan = "type: can, interface: can0, bitrate: 1000000";

// The rig's budgets at `tick_hz`, or the error with the temp path replaced by RIG.
std::string budget_error(const std::string& text, double tick_hz = 1000.0,
                         std::vector<BusBudgetResult>* out = nullptr) {
  TempFile f(text);
  try {
    const RigConfig r = load_rig_config(f.path(), head().layout);
    std::vector<std::string> warnings;
    auto results = check_bus_budgets(r, tick_hz);
    enforce_bus_budgets(results, warnings);
    if (out) *out = results;
    return warnings.empty() ? "ok" : warnings.front();
  } catch (const ConfigError& e) {
    std::string msg = e.what();
    const auto at = msg.find(f.path());
    if (at != std::string::npos) msg.replace(at, f.path().size(), "RIG");
    return msg;
  }
}

TEST(BusConfig, CanKeysReachTheBusOptions) {
  TempFile f(rig(kCan + ", protocol: custom, values: int32, rate_divider: 4, fd: true, "
                        "data_bitrate: 5000000, heartbeat_timeout_ms: 50"));
  const RigConfig r = load_rig_config(f.path(), head().layout);
  const BusConfig& b = r.buses.at(0);
  EXPECT_EQ(b.can_protocol, "custom");
  EXPECT_EQ(b.endpoint, "can0");
  EXPECT_EQ(b.can.width, custom_can::Width::kInt32);
  EXPECT_EQ(b.can.cycle_divider, 4);
  EXPECT_TRUE(b.can.fd);
  EXPECT_EQ(b.can.data_bitrate, 5'000'000);
  EXPECT_DOUBLE_EQ(b.can.heartbeat_timeout_s, 0.05);

  TempFile g(rig(kCan +
                 ", protocol: cia402, map_pdos: false, host_node: 100, drive_watchdog_ms: 60, "
                 "counts_per_rev: 65536, counts_per_mm: 2000"));
  const BusConfig c = load_rig_config(g.path(), head().layout).buses.at(0);
  EXPECT_EQ(c.can_protocol, "cia402");
  EXPECT_EQ(c.can.host_node, 100);
  EXPECT_FALSE(c.can.map_pdos);
  EXPECT_EQ(c.can.drive_watchdog_ms, 60);
  EXPECT_NEAR(c.can.rotary_counts_per_rad, 65536 / 6.283185307179586, 1e-9);
  EXPECT_DOUBLE_EQ(c.can.linear_counts_per_m, 2e6);
}

TEST(BusConfig, CiA402TimingKeysReachTheOptionsAndAHostNodeIdOnADriveIsRefused) {
  TempFile f(rig(kCan + ", protocol: cia402, feedback_timeout_ms: 30, quick_stop_ms: 250"));
  const BusConfig c = load_rig_config(f.path(), head().layout).buses.at(0);
  EXPECT_DOUBLE_EQ(c.can.feedback_timeout_s, 0.03);
  EXPECT_DOUBLE_EQ(c.can.quick_stop_s, 0.25);
  const std::string custom = budget_error(rig(kCan + ", quick_stop_ms: 100"));
  EXPECT_NE(custom.find("no quick_stop_ms on a custom bus"), std::string::npos) << custom;
  // Actuator a2 (address 2) on the host's own node id: line 7, its address.
  const std::string e = budget_error(rig(kCan + ", protocol: cia402, host_node: 2", 2));
  EXPECT_EQ(e.rfind("RIG:7:", 0), 0u) << e;
  EXPECT_NE(e.find("a node id other than the host's (host_node 2 on bus b0)"), std::string::npos)
      << e;
}

TEST(BusConfig, ModbusKeysReachTheTiming) {
  TempFile f(
      rig("type: modbus_rtu, device: /dev/ttyUSB0, baud: 115200, response_timeout_ms: 15, "
          "byte_timeout_ms: 2, retries: 2, fault_after_ms: 80, cycle_ms: 5, watchdog_ms: 250"));
  const BusConfig b = load_rig_config(f.path(), head().layout).buses.at(0);
  EXPECT_EQ(b.endpoint, "/dev/ttyUSB0");
  EXPECT_EQ(b.bitrate, 115200);
  EXPECT_DOUBLE_EQ(b.modbus.response_timeout_s, 0.015);
  EXPECT_DOUBLE_EQ(b.modbus.byte_timeout_s, 0.002);
  EXPECT_EQ(b.modbus.max_retries, 2);
  EXPECT_DOUBLE_EQ(b.modbus.board_timeout_s, 0.08);
  EXPECT_DOUBLE_EQ(b.modbus.cycle_period_s, 0.005);
  EXPECT_EQ(b.modbus.board_watchdog_ms, 250);
  EXPECT_EQ(b.modbus_registers.control, 0);
  EXPECT_EQ(b.modbus_registers.watchdog, 10);
  EXPECT_EQ(b.modbus_registers.status, 0);
  TempFile g(
      rig("type: modbus_tcp, host: 10.0.0.7:1502, enable_register: 40, "
          "watchdog_register: 7, status_register: 300"));
  EXPECT_EQ(load_rig_config(g.path(), head().layout).buses.at(0).modbus_registers.watchdog, 7);
  EXPECT_EQ(load_rig_config(g.path(), head().layout).buses.at(0).modbus_registers.status, 300);
  EXPECT_EQ(load_rig_config(g.path(), head().layout).buses.at(0).endpoint, "10.0.0.7:1502");
}

TEST(BusConfig, BadBusKeysNameTheirPositionKeyExpectedAndFound) {
  EXPECT_EQ(budget_error(rig(kCan + ", protocol: canopen")),
            "RIG:4:75: rig.buses[0].protocol: expected custom or cia402, found 'canopen'");
  EXPECT_EQ(budget_error(rig(kCan + ", protocol: cia402, fd: true")),
            "RIG:4:87: rig.buses[0].fd: expected no fd on a cia402 bus (CAN FD is for custom "
            "boards), found 'true'");
  EXPECT_EQ(budget_error(rig(kCan + ", values: int8")),
            "RIG:4:73: rig.buses[0].values: expected int16 or int32, found 'int8'");
  EXPECT_EQ(budget_error(rig(kCan + ", data_bitrate: 2000000")),
            "RIG:4:79: rig.buses[0].data_bitrate: expected data_bitrate only with fd: true, "
            "found fd: false");
  EXPECT_EQ(budget_error(rig(kCan + ", rate_divider: 0")),
            "RIG:4:79: rig.buses[0].rate_divider: expected an integer in [1, 100], found '0'");
  EXPECT_EQ(budget_error(rig(kCan + ", retries: 1")),
            "RIG:4:65: rig.buses[0].retries: expected one of: name, type, interface, bitrate, "
            "protocol, rate_divider, fd, data_bitrate, values, heartbeat_timeout_ms, map_pdos, "
            "host_node, "
            "host_heartbeat_ms, drive_heartbeat_ms, drive_watchdog_ms, sdo_timeout_ms, "
            "enable_timeout_ms, counts_per_rev, counts_per_mm, feedback_timeout_ms, quick_stop_ms, "
            "found unknown key 'retries'");
  const std::string rtu = "type: modbus_rtu, device: /dev/ttyS0, baud: 115200";
  EXPECT_EQ(budget_error(rig(rtu + ", response_timeout_ms: 500")),
            "RIG:4:92: rig.buses[0].response_timeout_ms: expected a number in [1, 250], found "
            "'500'");
  EXPECT_EQ(budget_error(rig(rtu + ", enable_register: 20, watchdog_register: 25")),
            "RIG:4:111: rig.buses[0].watchdog_register: expected a register outside the enable "
            "block [20, 30) (CONTROL, HEARTBEAT, 8 targets), found '25'");
  EXPECT_EQ(budget_error(rig(rtu + ", retries: 9")),
            "RIG:4:80: rig.buses[0].retries: expected an integer in [0, 5], found '9'");
  EXPECT_EQ(budget_error(rig(rtu + ", response_timeout_ms: 40, retries: 2, fault_after_ms: 100")),
            "RIG:4:124: rig.buses[0].fault_after_ms: expected fault_after_ms above (retries + 1) "
            "x response_timeout_ms = 120 ms, found 100 ms");
}

TEST(BusBudget, TheDefaultRigPassesWithItsDividerAndWouldBeRefusedWithout) {
  const LoadedConfig cfg = load_config(default_config_path());
  ASSERT_EQ(cfg.budgets.size(), 2u);
  EXPECT_EQ(cfg.budgets[0].text,
            "can0: 8 frames per cycle at 250 Hz = 270000 bit/s, 27.0% of 1000000 bit/s");
  EXPECT_EQ(cfg.budgets[0].verdict, BusBudgetResult::Verdict::kOk);
  EXPECT_EQ(cfg.budgets[1].verdict, BusBudgetResult::Verdict::kOk) << cfg.budgets[1].text;
  EXPECT_NEAR(cfg.budgets[1].load, 0.84, 1e-9);  // 168 characters at 1 Mbaud in 2 ms

  // 12 axes on custom boards every tick: 108%, refused with the numbers.
  EXPECT_EQ(budget_error(rig(kCan, 12)),
            "RIG:4:7: rig.buses 'b0': expected a bus load of at most 70%, found b0: 8 frames "
            "per cycle at 1000 Hz = 1080000 bit/s, 108.0% of 1000000 bit/s (refused: above "
            "70%); raise rate_divider, use protocol: custom (several actuators per frame) or "
            "fd: true, or split the bus");
  // Every second tick: 54%, a warning.
  EXPECT_EQ(budget_error(rig(kCan + ", rate_divider: 2", 12)),
            "warning: b0: 8 frames per cycle at 500 Hz = 540000 bit/s, 54.0% of 1000000 "
            "bit/s (warning: above 50%)");
  // CiA 402 drives, one frame pair each plus SYNC and heartbeats: refused even at 250 Hz.
  EXPECT_NE(budget_error(rig(kCan + ", protocol: cia402, rate_divider: 4", 12))
                .find("28 frames per cycle at 250 Hz = 945000 bit/s, 94.5%"),
            std::string::npos);
}

TEST(BusBudget, CanFdFramesAreBudgetedAtTheirOwnWorstCase) {
  EXPECT_EQ(can_fd_length(26), 32);
  EXPECT_EQ(can_fd_length(8), 8);
  EXPECT_EQ(can_fd_length(49), 64);
  // 8 data bytes without a bit rate switch: 34 nominal + 114 data-phase bits.
  EXPECT_DOUBLE_EQ(can_fd_frame_bits(8, 1'000'000, 1'000'000), 148.0);
  // 12 int16 channels on one FD board: 26 bytes sent as 32; the data phase
  // (359 bits) at 5 Mbit/s takes 71.8 nominal bit times.
  EXPECT_NEAR(can_fd_frame_bits(26, 1'000'000, 5'000'000), 34.0 + 359.0 / 5.0, 1e-9);
  std::vector<BusBudgetResult> r;
  EXPECT_EQ(budget_error(rig(kCan + ", fd: true, data_bitrate: 5000000", 12), 1000.0, &r), "ok");
  EXPECT_EQ(r.at(0).can.frames_per_cycle, 2);
  EXPECT_NEAR(r.at(0).load, 2 * (34.0 + 71.8) * 1000.0 / 1e6, 1e-9);  // 21.2% every tick
  // Without the switch the same frames are 393 bits each: 78.6%, refused.
  EXPECT_NE(budget_error(rig(kCan + ", fd: true", 12)).find("78.6%"), std::string::npos);
}

TEST(BusBudget, AddressesTheProtocolCannotCarryAreRefusedAtTheActuator) {
  std::string text = rig(kCan + ", protocol: cia402");
  text.replace(text.find("address: 1"), 10, "address: 128");
  EXPECT_EQ(budget_error(text),
            "RIG:6:7: rig.actuators 'a1'.address: expected 1..127 on cia402 bus b0, found 128");
}

// A runtime file around `extra` top-level blocks.
std::string runtime(const std::string& extra) {
  return "head: h\nrig: r\nexpressions: e\n" + extra;
}

TEST(HardwareConfig, HardwareSafetyIoAndGamepadBlocksParse) {
  const LoadedConfig cfg = load_config(default_config_path());
  EXPECT_EQ(cfg.runtime.hardware, HardwareMode::kSim);
  ASSERT_TRUE(cfg.runtime.safety_io.has_value());
  EXPECT_EQ(cfg.runtime.safety_io->chip, "gpiochip0");
  EXPECT_EQ(cfg.runtime.safety_io->gpio.estop_line, 17u);
  EXPECT_FALSE(cfg.runtime.safety_io->gpio.estop_active_low);
  EXPECT_EQ(cfg.runtime.safety_io->gpio.led_line, 22);
  ASSERT_TRUE(cfg.runtime.gamepad.has_value());
  const GamepadConfig& g = *cfg.runtime.gamepad;
  EXPECT_EQ(g.selector.vendor, 0x1209);
  EXPECT_EQ(g.selector.product, 0xFACE);
  ASSERT_EQ(g.terms.size(), 8u);
  // jaw_pitch_deg = 9 + 9·y degrees, in radians.
  EXPECT_EQ(g.terms[0].signal, cfg.head.layout.jaw_pitch());
  EXPECT_NEAR(g.terms[0].gain, 9.0 * 3.14159265358979 / 180.0, 1e-9);
  EXPECT_NEAR(g.terms[0].offset, 9.0 * 3.14159265358979 / 180.0, 1e-9);
  EXPECT_EQ(g.terms[2].source, GamepadTerm::Source::kButton);

  ConfigOverrides o;
  o.hardware = HardwareMode::kReal;
  EXPECT_EQ(load_config(default_config_path(), o).runtime.hardware, HardwareMode::kReal);
}

std::string runtime_error(const std::string& text) {
  TempFile f(text);
  try {
    load_runtime_config(f.path());
  } catch (const ConfigError& e) {
    std::string msg = e.what();
    const auto at = msg.find(f.path());
    if (at != std::string::npos) msg.replace(at, f.path().size(), "RT");
    return msg;
  }
  return "ok";
}

TEST(HardwareConfig, BadBlocksNameTheirPositionKeyExpectedAndFound) {
  EXPECT_EQ(runtime_error(runtime("hardware: yes\n")),
            "RT:4:11: hardware: expected sim or real, found 'yes'");
  EXPECT_EQ(runtime_error(runtime("safety_io: { estop_line: 3, power_line: 3 }\n")),
            "RT:4:41: safety_io.power_line: expected a line other than estop_line, found '3'");
  EXPECT_EQ(
      runtime_error(runtime("safety_io: { estop_line: 3, power_line: 4, estop_active: up }\n")),
      "RT:4:58: safety_io.estop_active: expected high or low, found 'up'");
  EXPECT_EQ(runtime_error(runtime("gamepad: { vendor: 0x1209, map: [] }\n")),
            "RT:4:10: gamepad: expected either path, or vendor and product, found neither");
  EXPECT_EQ(runtime_error(runtime("gamepad: { path: /dev/hidraw0, axes: [{ name: x, byte: 0 }], "
                                  "map: [{ axis: z, signal: jaw_pitch_deg }] }\n")),
            "RT:4:76: gamepad.map[0].axis: expected the name of one of the gamepad's axes (x), "
            "found 'z'");
}

TEST(HardwareConfig, AGamepadWithoutAxesOrButtonsTakesTheDescriptorsNamedSlots) {
  TempFile f(runtime(
      "gamepad: { vendor: 0x054c, product: 0x05c4, map: [{ axis: hat_y, signal: jaw_pitch_deg }, "
      "{ button: button_2, signal: jaw_yaw_deg }] }\n"));
  const RuntimeConfig rt = load_runtime_config(f.path());
  const GamepadConfig& g = *rt.gamepad;
  EXPECT_TRUE(g.layout.axes.empty() && g.layout.buttons.empty()) << "read at each open";
  ASSERT_EQ(g.pending.size(), 2u);
  EXPECT_EQ(g.pending[0].term.input, 10u);  // kDescriptorAxisNames: hat_y
  EXPECT_EQ(g.pending[1].term.input, 1u);   // button_2
  EXPECT_EQ(runtime_error(runtime("gamepad: { path: /dev/hidraw0, map: [{ axis: throttle, "
                                  "signal: jaw_pitch_deg }] }\n")),
            "RT:4:46: gamepad.map[0].axis: expected the name of one of the gamepad's axes (x, y, "
            "z, rx, ry, rz, slider, dial, wheel, hat_x, hat_y, accelerator, brake), found "
            "'throttle'");
}

TEST(HardwareConfig, HandWrittenAxesMayBeBitFields) {
  TempFile f(
      runtime("gamepad: { path: /dev/hidraw0, axes: [{ name: lx, byte: 1, bit: 4, bits: 12 "
              "}], map: [{ axis: lx, signal: jaw_pitch_deg }] }\n"));
  const GamepadLayout l = load_runtime_config(f.path()).gamepad->layout;
  ASSERT_EQ(l.axes.size(), 1u);
  EXPECT_EQ(l.axes[0].bit, 4);
  EXPECT_EQ(l.axes[0].bits, 12);
  EXPECT_DOUBLE_EQ(l.axes[0].max, 4095.0);
  EXPECT_EQ(runtime_error(runtime("gamepad: { path: /dev/hidraw0, axes: [{ name: lx, byte: 63, "
                                  "bits: 16 }], map: [{ axis: lx, signal: jaw_pitch_deg }] }\n")),
            "RT:4:57: gamepad.axes[0].byte: expected a field that ends within 64 bytes (byte * "
            "8 + bit + bits <= 512), found '63'");
}

TEST(HardwareConfig, AGamepadSignalTheHeadDoesNotHaveIsNamed) {
  TempFile f(
      runtime("gamepad: { path: /dev/hidraw0, buttons: [{ name: a, byte: 0, bit: 0 }], "
              "map: [{ button: a, signal: jaw_roll_deg }] }\n"));
  RuntimeConfig rt = load_runtime_config(f.path());
  try {
    resolve_gamepad_terms(*rt.gamepad, head().layout);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              f.path() +
                  ":4:100: gamepad.map[0].signal: expected a face signal of the head "
                  "(muscle name, jaw_pitch_deg, eyelid_closure_l, ...), found unknown "
                  "signal 'jaw_roll_deg'");
  }
}

// An actuator's `encoding` against its bus (firmware-host/model/rig_encoding_check.hpp).

// One rotary actuator, hardware range -6..20 deg, on one bus; `encoding` is
// its flow mapping or empty.
std::string encoded_rig(const std::string& bus, const std::string& encoding) {
  return "rig:\n  name: t\n  buses:\n    - { name: b0, " + bus +
         " }\n  actuators:\n    - { name: a1, kind: rotary, bus: b0, address: 1, "
         "position_deg: { min: -6, max: 20 }, max_velocity_deg_s: 100, "
         "max_acceleration_deg_s2: 1000, rest_deg: 0, map: { terms: { jaw_pitch_deg: 1 } }" +
         (encoding.empty() ? "" : ", encoding: " + encoding) + " }\n";
}

// Where its encoding's flow mapping starts: RIG:6:<column>.
std::string at(const std::string& text) {
  const std::size_t line6 = text.find("    - { name: a1");
  return "RIG:6:" + std::to_string(text.find("encoding: ", line6) + 10 - line6 + 1);
}

const std::string kModbus = "type: modbus_tcp, host: 127.0.0.1";

TEST(RigEncoding, ARawTypeThatCannotCarryTheRangeIsRefusedWithItsPlace) {
  const std::string text = encoded_rig(kModbus, "{ raw: uint16, scale: 100 }");
  EXPECT_EQ(budget_error(text),
            at(text) +
                ": actuator a1 encoding: expected the hardware range to fit strictly inside raw "
                "uint16 (0, 65535), found position -6 deg encoding to -600 counts");
  const std::string wide = encoded_rig(kModbus, "{ raw: int16, scale: 2000 }");  // 20 deg -> 40000
  EXPECT_EQ(budget_error(wide),
            at(wide) +
                ": actuator a1 encoding: expected the hardware range to fit strictly inside raw "
                "int16 (-32767, 32767), found position 20 deg encoding to 40000 "
                "counts");
  EXPECT_EQ(budget_error(encoded_rig(kModbus, "{ raw: uint16, scale: 50, offset: 32768 }")), "ok");
  // The hardware minimum on the raw limit itself: a saturated reading there
  // could hide the actuator beyond its range, so it is refused too.
  const std::string edge = encoded_rig(kModbus, "{ raw: uint16, scale: 100, offset: 600 }");
  EXPECT_EQ(budget_error(edge),
            at(edge) +
                ": actuator a1 encoding: expected the hardware range to fit strictly inside raw "
                "uint16 (0, 65535), found position -6 deg encoding to 0 counts");
}

TEST(RigEncoding, Int32IsRefusedOnModbusAndInTwoByteCanFields) {
  const std::string modbus = encoded_rig(kModbus, "{ raw: int32, scale: 10000 }");
  EXPECT_EQ(budget_error(modbus),
            at(modbus) +
                ": actuator a1 encoding: expected raw int16 or uint16 on Modbus bus b0 (one "
                "register per channel), found raw int32");
  const std::string can = encoded_rig(kCan + ", protocol: custom, values: int16", "{ raw: int32 }");
  EXPECT_EQ(budget_error(can), at(can) +
                                   ": actuator a1 encoding: expected raw int16 or uint16 on bus b0 "
                                   "(values: int16, 2-byte fields), found raw int32");
  EXPECT_EQ(budget_error(encoded_rig(kCan + ", protocol: custom, values: int32", "{ raw: int32 }")),
            "ok");
}

TEST(RigEncoding, CiA402DrivesTakeAnInt32EncodingOnly) {
  const std::string cia = kCan + ", protocol: cia402, rate_divider: 4";
  const std::string i16 = encoded_rig(cia, "{ raw: int16, scale: 100 }");
  EXPECT_EQ(budget_error(i16), at(i16) +
                                   ": actuator a1 encoding: expected raw int32 on CiA 402 bus b0 "
                                   "(drives count in 32 bits), found raw int16");
  const std::string u16 = encoded_rig(cia, "{ raw: uint16, scale: 100 }");
  EXPECT_EQ(budget_error(u16), at(u16) +
                                   ": actuator a1 encoding: expected raw int32 on CiA 402 bus b0 "
                                   "(drives count in 32 bits), found raw uint16");
  EXPECT_EQ(budget_error(encoded_rig(cia, "{ raw: int32, scale: 2000, offset: -40000 }")), "ok");
  EXPECT_EQ(budget_error(encoded_rig(cia, "")), "ok");  // the bus's counts_per_rev
  // 20 deg at 2e8 counts per deg is beyond int32.
  const std::string wide = encoded_rig(cia, "{ raw: int32, scale: 2e8 }");
  EXPECT_EQ(budget_error(wide),
            at(wide) +
                ": actuator a1 encoding: expected the hardware range to fit strictly inside raw "
                "int32 (-2.14748e+09, 2.14748e+09), found position 20 deg encoding to 4e+09 "
                "counts");
  // Without an encoding, the bus's counts must fit too: 20 deg at 1e11 counts per rev.
  const std::string bus = encoded_rig(cia + ", counts_per_rev: 1e11", "");
  EXPECT_NE(budget_error(bus).find("actuator a1 encoding: expected the hardware range to fit "
                                   "strictly inside raw int32 (-2.14748e+09, 2.14748e+09), found "
                                   "position 20 deg encoding to 5.55556e+09 counts"),
            std::string::npos)
      << budget_error(bus);
}

TEST(RigEncoding, AnActuatorWithoutEncodingTakesItsBusDefault) {
  TempFile i32(encoded_rig(kCan + ", protocol: custom, values: int32", ""));
  const ActuatorEncoding e = load_rig_config(i32.path(), head().layout).actuators[0].model.encoding;
  EXPECT_EQ(e.raw, ActuatorEncoding::Raw::kInt32);  // 0.0001 deg per count, as before encodings
  EXPECT_EQ(e.scale, 10000.0);
  TempFile mb(encoded_rig(kModbus, "{ raw: uint16, scale: 50, offset: 32768 }"));
  const ActuatorEncoding m = load_rig_config(mb.path(), head().layout).actuators[0].model.encoding;
  EXPECT_EQ(m.raw, ActuatorEncoding::Raw::kUint16);
  EXPECT_EQ(m.offset, 32768.0);
  TempFile i16(encoded_rig(kCan, ""));
  EXPECT_EQ(load_rig_config(i16.path(), head().layout).actuators[0].model.encoding.scale, 100.0);
}

// ---- PCA9685 buses (docs/CONFIG.md, "PCA9685").

const std::string kPca = "type: pca9685, device: /dev/i2c-1";
const std::string kServoUs = "{ raw: uint16, scale: 10, offset: 1500 }";

// `count` servos on a PCA9685 bus, addresses 1..count, pulses 1440..1700 µs.
std::string pca_rig(const std::string& bus, int count) {
  std::string s = "rig:\n  name: t\n  buses:\n    - { name: b0, " + bus + " }\n  actuators:\n";
  for (int i = 1; i <= count; ++i) {
    s += "    - { name: a" + std::to_string(i) +
         ", kind: rotary, bus: b0, address: " + std::to_string(i) +
         ", position_deg: { min: -6, max: 20 }, max_velocity_deg_s: 100, "
         "max_acceleration_deg_s2: 1000, rest_deg: 0, map: { terms: { jaw_pitch_deg: 1 } }, "
         "encoding: " +
         kServoUs + " }\n";
  }
  return s;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(BusConfig, Pca9685KeysReachTheOptions) {
  TempFile f(pca_rig(kPca + ", boards: [0x40, 0x41], pwm_hz: 60, i2c_khz: 400, cycle_ms: 10", 1));
  const BusConfig b = load_rig_config(f.path(), head().layout).buses.at(0);
  EXPECT_TRUE(b.is_pca9685());
  EXPECT_EQ(b.endpoint, "/dev/i2c-1");
  EXPECT_EQ(b.pca9685.boards, (std::vector<int>{0x40, 0x41}));
  EXPECT_DOUBLE_EQ(b.pca9685.pwm_hz, 60.0);
  EXPECT_EQ(b.pca9685.i2c_hz, 400'000);
  EXPECT_DOUBLE_EQ(b.pca9685.cycle_period_s, 0.010);
  TempFile g(pca_rig(kPca, 1));  // defaults
  const BusConfig d = load_rig_config(g.path(), head().layout).buses.at(0);
  EXPECT_EQ(d.pca9685.boards, (std::vector<int>{0x40}));
  EXPECT_DOUBLE_EQ(d.pca9685.pwm_hz, 50.0);
  EXPECT_EQ(d.pca9685.i2c_hz, 100'000);
}

TEST(BusConfig, BadPca9685KeysNameTheirPositionKeyExpectedAndFound) {
  const auto err = [](const std::string& bus) { return budget_error(pca_rig(bus, 1)); };
  std::string e = err(kPca + ", boards: [0x40, 0x40]");
  EXPECT_TRUE(contains(e, "RIG:4:") && contains(e,
                                                "rig.buses[0].boards[1]: expected a board "
                                                "address not listed before, found 64"))
      << e;
  e = err(kPca + ", boards: [0x20]");
  EXPECT_TRUE(contains(e, "rig.buses[0].boards[0]: expected an integer in [64, 127]")) << e;
  e = err(kPca + ", boards: []");
  EXPECT_TRUE(contains(e, "rig.buses[0].boards: expected at least one board address")) << e;
  e = err(kPca + ", pwm_hz: 2000");
  EXPECT_TRUE(contains(e, "rig.buses[0].pwm_hz: expected a number in [24, 1526], found '2000'"))
      << e;
  e = err(kPca + ", baud: 115200");
  EXPECT_TRUE(contains(e,
                       "rig.buses[0].baud: expected one of: name, type, device, boards, "
                       "pwm_hz, i2c_khz, cycle_ms, found unknown key 'baud'"))
      << e;
  e = budget_error(pca_rig("type: pca9685", 1));
  EXPECT_TRUE(contains(e, "rig.buses[0]") && contains(e, "device")) << e;
}

TEST(BusBudget, Pca9685ClocksPerCycleAt100And400Khz) {
  // 10 channels on one board: writes of 8 and 2 channels (308 + 92 clocks)
  // and the MODE1 read (39): 439 clocks in a 1 / 50.03 Hz cycle.
  std::vector<BusBudgetResult> r;
  EXPECT_EQ(budget_error(pca_rig(kPca, 10), 1000.0, &r), "ok");
  EXPECT_TRUE(contains(r.at(0).text, "439 I2C clocks per I/O cycle = 4.39 ms at 100 kHz, 22%"))
      << r.at(0).text;
  EXPECT_EQ(budget_error(pca_rig(kPca + ", i2c_khz: 400", 10), 1000.0, &r), "ok");
  EXPECT_TRUE(contains(r.at(0).text, "= 1.10 ms at 400 kHz, 5%")) << r.at(0).text;
  // Two full boards at 100 kHz in a 5 ms cycle cannot keep up: a warning.
  const std::string busy =
      budget_error(pca_rig(kPca + ", boards: [0x40, 0x41], cycle_ms: 5", 32), 1000.0, &r);
  EXPECT_TRUE(contains(busy, "warning: b0: 2 PCA9685 boards, 1310 I2C clocks")) << busy;
  // Address 17 needs a second board.
  const std::string far = budget_error(pca_rig(kPca, 17));
  EXPECT_TRUE(contains(far, "rig.actuators 'a17'.address: expected 1..16 on PCA9685 bus b0"))
      << far;
}

TEST(RigEncoding, Pca9685TakesAMicrosecondPulseInsideThePeriod) {
  const std::string none = encoded_rig(kPca, "");
  EXPECT_TRUE(contains(budget_error(none),
                       "expected raw uint16 on PCA9685 bus b0 (the pulse "
                       "width in µs), found no encoding"))
      << budget_error(none);
  const std::string i16 = encoded_rig(kPca, "{ raw: int16, scale: 10, offset: 1500 }");
  EXPECT_EQ(budget_error(i16), at(i16) +
                                   ": actuator a1 encoding: expected raw uint16 on PCA9685 bus b0 "
                                   "(the pulse width in µs), found raw int16");
  EXPECT_EQ(budget_error(encoded_rig(kPca, kServoUs)), "ok");
  // pwm_hz 1000 runs at 1017.25 Hz (PRE_SCALE 5): 983 µs, too short for 1440..1700 µs.
  const std::string fast = encoded_rig(kPca + ", pwm_hz: 1000", kServoUs);
  EXPECT_TRUE(contains(budget_error(fast),
                       "expected pulses inside the 983.04 µs PWM period of "
                       "bus b0, found position -6 deg giving 1440 µs"))
      << budget_error(fast);
}

}  // namespace
}  // namespace facectl

namespace facectl {
namespace {

const std::string kDxl = "type: dynamixel, device: /dev/ttyUSB0, baud: 1000000";

TEST(BusConfig, DynamixelKeysReachTheOptions) {
  TempFile f(rig(kDxl + ", response_timeout_ms: 4, fault_after_ms: 60, cycle_ms: 8, "
                        "return_delay_us: 20, watchdog_ms: 200, write_position_limits: false"));
  const BusConfig b = load_rig_config(f.path(), head().layout).buses.at(0);
  EXPECT_EQ(b.endpoint, "/dev/ttyUSB0");
  EXPECT_EQ(b.bitrate, 1000000);
  EXPECT_DOUBLE_EQ(b.dynamixel.response_timeout_s, 0.004);
  EXPECT_DOUBLE_EQ(b.dynamixel.fault_after_s, 0.06);
  EXPECT_DOUBLE_EQ(b.dynamixel.cycle_period_s, 0.008);
  EXPECT_EQ(b.dynamixel.return_delay_us, 20);
  EXPECT_EQ(b.dynamixel.bus_watchdog_ms, 200);
  EXPECT_FALSE(b.dynamixel.write_position_limits);
}

TEST(BusConfig, BadDynamixelKeysNameTheirPositionKeyExpectedAndFound) {
  EXPECT_EQ(budget_error(rig("type: dynamixel, device: /dev/ttyUSB0, baud: 250000")),
            "RIG:4:64: rig.buses[0].baud: expected a rate a DYNAMIXEL X servo runs at: 9600, "
            "57600, 115200, 1000000, 2000000, 3000000, 4000000 or 4500000, found '250000'");
  EXPECT_EQ(budget_error(rig(kDxl + ", watchdog_ms: 30")),
            "RIG:4:86: rig.buses[0].watchdog_ms: expected 0 (off) or a multiple of 20 ms (the "
            "servo's unit), found '30'");
  EXPECT_EQ(budget_error(rig(kDxl + ", return_delay_us: 3")),
            "RIG:4:90: rig.buses[0].return_delay_us: expected an even number of microseconds "
            "(the unit is 2 us), found '3'");
  EXPECT_EQ(budget_error(rig(kDxl + ", response_timeout_ms: 50, fault_after_ms: 40")),
            "RIG:4:114: rig.buses[0].fault_after_ms: expected fault_after_ms above "
            "response_timeout_ms (50 ms), found 40 ms");
  EXPECT_EQ(budget_error(rig(kDxl + ", cycle_ms: 20, watchdog_ms: 20")),
            "RIG:4:100: rig.buses[0].watchdog_ms: expected 0 (off) or at least twice cycle_ms "
            "(40 ms), found '20'");
}

TEST(RigEncoding, DynamixelServosTakePulsesOfOneTurn) {
  // Without an encoding: 4096 pulses a turn, 0 deg at the centre.
  TempFile f(encoded_rig(kDxl, ""));
  const RigConfig r = load_rig_config(f.path(), head().layout);
  EXPECT_EQ(r.actuators.at(0).model.encoding.raw, ActuatorEncoding::Raw::kInt32);
  EXPECT_DOUBLE_EQ(r.actuators.at(0).model.encoding.scale, 4096.0 / 360.0);
  EXPECT_DOUBLE_EQ(r.actuators.at(0).model.encoding.offset, 2048.0);
  const std::string low = encoded_rig(kDxl, "{ raw: int32, scale: 11.377778, offset: 0 }");
  EXPECT_EQ(budget_error(low),
            at(low) +
                ": actuator a1 encoding: expected the hardware range within 0..4095 pulses (one "
                "turn, position control mode) on DYNAMIXEL bus b0, found position -6 deg "
                "encoding to -68 pulses");
  const std::string narrow = encoded_rig(kDxl, "{ raw: uint16, scale: 11.377778, offset: 2048 }");
  EXPECT_EQ(budget_error(narrow), at(narrow) +
                                      ": actuator a1 encoding: expected raw int32 on DYNAMIXEL "
                                      "bus b0 (positions are 4 bytes), found raw uint16");
  std::vector<BusBudgetResult> results;
  EXPECT_EQ(budget_error(rig(kDxl, 10), 1000.0, &results), "ok");
  // Ten servos at 1 Mbit/s: 64 + 24 + 320 bytes, 4.08 ms of the 5 ms cycle.
  EXPECT_EQ(results.at(0).text,
            "b0: 10 servos, 408 bytes per I/O cycle = 4.08 ms at 1000000 baud, 82% of the 5 ms "
            "cycle");
}

const std::string kSts = "type: feetech, device: /dev/ttyUSB0, baud: 1000000, series: sts";
const std::string kScs = "type: feetech, device: /dev/ttyUSB0, baud: 1000000, series: scs";

TEST(BusConfig, FeetechKeysReachTheOptions) {
  TempFile f(rig(kScs + ", response_timeout_ms: 4, fault_after_ms: 60, cycle_ms: 8, "
                        "reconnect_ms: 250, return_delay_us: 20, write_position_limits: false"));
  const BusConfig b = load_rig_config(f.path(), head().layout).buses.at(0);
  EXPECT_TRUE(b.is_feetech());
  EXPECT_EQ(b.endpoint, "/dev/ttyUSB0");
  EXPECT_EQ(b.bitrate, 1000000);
  EXPECT_EQ(b.feetech.series, ft::Series::kScs);
  EXPECT_DOUBLE_EQ(b.feetech.response_timeout_s, 0.004);
  EXPECT_DOUBLE_EQ(b.feetech.fault_after_s, 0.06);
  EXPECT_DOUBLE_EQ(b.feetech.cycle_period_s, 0.008);
  EXPECT_DOUBLE_EQ(b.feetech.reconnect_interval_s, 0.25);
  EXPECT_EQ(b.feetech.return_delay_us, 20);
  EXPECT_FALSE(b.feetech.write_position_limits);
}

TEST(BusConfig, BadFeetechKeysNameTheirPositionKeyExpectedAndFound) {
  const auto has = [](const std::string& error, const std::string& part) {
    return error.find(part) != std::string::npos && error.rfind("RIG:4:", 0) == 0;
  };
  std::string e = budget_error(rig("type: feetech, device: /dev/ttyUSB0, baud: 9600, series: sts"));
  EXPECT_TRUE(has(e,
                  "rig.buses[0].baud: expected a rate a Feetech servo runs at: 38400, 57600, "
                  "76800, 115200, 128000, 250000, 500000 or 1000000, found '9600'"))
      << e;
  e = budget_error(rig("type: feetech, device: /dev/ttyUSB0, baud: 1000000, series: xl"));
  EXPECT_TRUE(has(e,
                  "rig.buses[0].series: expected sts (STS/SMS, e.g. STS3215) or scs (SCS, "
                  "e.g. SCS0009), found 'xl'"))
      << e;
  e = budget_error(rig("type: feetech, device: /dev/ttyUSB0, baud: 1000000"));
  EXPECT_NE(e.find("series"), std::string::npos) << e;
  e = budget_error(rig(kSts + ", return_delay_us: 3"));
  EXPECT_TRUE(has(e, "rig.buses[0].return_delay_us: expected an even number of microseconds")) << e;
  e = budget_error(rig(kSts + ", response_timeout_ms: 50, fault_after_ms: 40"));
  EXPECT_TRUE(has(e,
                  "rig.buses[0].fault_after_ms: expected fault_after_ms above "
                  "response_timeout_ms (50 ms), found 40 ms"))
      << e;
  e = budget_error(rig(kSts + ", watchdog_ms: 100"));
  EXPECT_NE(e.find("watchdog_ms"), std::string::npos) << e;  // Feetech servos have none
}

TEST(RigEncoding, FeetechServosTakeStepsOfTheirSeries) {
  // STS without an encoding: 4096 steps a turn, 0 deg at the centre.
  TempFile sts(encoded_rig(kSts, ""));
  const RigConfig r = load_rig_config(sts.path(), head().layout);
  EXPECT_EQ(r.actuators.at(0).model.encoding.raw, ActuatorEncoding::Raw::kUint16);
  EXPECT_DOUBLE_EQ(r.actuators.at(0).model.encoding.scale, 4096.0 / 360.0);
  EXPECT_DOUBLE_EQ(r.actuators.at(0).model.encoding.offset, 2048.0);
  // SCS: 1024 steps over 300 deg.
  TempFile scs(encoded_rig(kScs, ""));
  const RigConfig c = load_rig_config(scs.path(), head().layout);
  EXPECT_DOUBLE_EQ(c.actuators.at(0).model.encoding.scale, 1024.0 / 300.0);
  EXPECT_DOUBLE_EQ(c.actuators.at(0).model.encoding.offset, 512.0);
  // 1024 steps a turn fit an STS, not an SCS at its upper end.
  const std::string wide = encoded_rig(kScs, "{ raw: uint16, scale: 50, offset: 512 }");
  EXPECT_EQ(budget_error(wide),
            at(wide) +
                ": actuator a1 encoding: expected the hardware range within 0..1023 pulses (the "
                "travel of an SCS servo) on Feetech SCS bus b0, found position 20 deg encoding "
                "to 1512 pulses");
  const std::string wide32 = encoded_rig(kSts, "{ raw: int32, scale: 11.377778, offset: 2048 }");
  EXPECT_EQ(budget_error(wide32), at(wide32) +
                                      ": actuator a1 encoding: expected raw uint16 on Feetech "
                                      "STS bus b0 (positions are 2 bytes), found raw int32");
  std::vector<BusBudgetResult> results;
  EXPECT_EQ(budget_error(rig(kSts, 10), 1000.0, &results), "ok");
  // Ten STS servos at 1 Mbit/s: sync write 6+2+30, sync read 6+2+10, ten
  // 14-byte replies: 196 bytes, 1.96 ms of the 10 ms cycle.
  EXPECT_EQ(results.at(0).text,
            "b0: 10 servos, 196 bytes per I/O cycle = 1.96 ms at 1000000 baud, 20% of the 10 ms "
            "cycle");
  // SCS reads each servo on its own: ten 8-byte reads instead of one sync read.
  EXPECT_EQ(budget_error(rig(kScs, 10), 1000.0, &results), "ok");
  EXPECT_EQ(results.at(0).text,
            "b0: 10 servos, 258 bytes per I/O cycle = 2.58 ms at 1000000 baud, 26% of the 10 ms "
            "cycle");
  // At 38400 baud the cycle outlasts fault_after_ms: refused.
  const std::string slow = rig("type: feetech, device: /dev/ttyUSB0, baud: 38400, series: scs", 20);
  EXPECT_NE(budget_error(slow).find("refused: not under fault_after_ms"), std::string::npos)
      << budget_error(slow);
}

}  // namespace
}  // namespace facectl

namespace facectl {
namespace {

const std::string kMaestro = "type: maestro, device: /dev/ttyACM0, baud: 115200";

TEST(BusConfig, MaestroKeysReachTheOptions) {
  TempFile f(pca_rig(kMaestro + ", protocol: pololu, device_number: 13, multiple_targets: true, "
                                "cycle_ms: 10, response_timeout_ms: 8, fault_after_ms: 80, "
                                "reconnect_ms: 250",
                     1));
  const BusConfig b = load_rig_config(f.path(), head().layout).buses.at(0);
  EXPECT_TRUE(b.is_maestro());
  EXPECT_EQ(b.endpoint, "/dev/ttyACM0");
  EXPECT_EQ(b.bitrate, 115200);
  EXPECT_EQ(b.maestro.protocol, maestro::Protocol::kPololu);
  EXPECT_EQ(b.maestro.device_number, 13);
  EXPECT_TRUE(b.maestro.multiple_targets);
  EXPECT_DOUBLE_EQ(b.maestro.cycle_period_s, 0.010);
  EXPECT_DOUBLE_EQ(b.maestro.response_timeout_s, 0.008);
  EXPECT_DOUBLE_EQ(b.maestro.fault_after_s, 0.080);
  EXPECT_DOUBLE_EQ(b.maestro.reconnect_interval_s, 0.250);
  TempFile g(pca_rig(kMaestro, 1));  // defaults
  const BusConfig d = load_rig_config(g.path(), head().layout).buses.at(0);
  EXPECT_EQ(d.maestro.protocol, maestro::Protocol::kCompact);
  EXPECT_EQ(d.maestro.device_number, 12);
  EXPECT_FALSE(d.maestro.multiple_targets);
  EXPECT_DOUBLE_EQ(d.maestro.cycle_period_s, 0.020);
}

TEST(BusConfig, BadMaestroKeysNameTheirPositionKeyExpectedAndFound) {
  const auto err = [](const std::string& bus) { return budget_error(pca_rig(bus, 1)); };
  EXPECT_EQ(err("type: maestro, device: /dev/ttyACM0, baud: 250000"),
            "RIG:4:62: rig.buses[0].baud: expected an integer in [300, 200000], found '250000'");
  EXPECT_EQ(err(kMaestro + ", protocol: mini_ssc"),
            "RIG:4:80: rig.buses[0].protocol: expected compact or pololu, found 'mini_ssc'");
  EXPECT_EQ(err(kMaestro + ", device_number: 13"),
            "RIG:4:85: rig.buses[0].device_number: expected device_number only with protocol: "
            "pololu, found protocol: compact");
  EXPECT_EQ(err(kMaestro + ", protocol: pololu, device_number: 128"),
            "RIG:4:103: rig.buses[0].device_number: expected an integer in [0, 127], found '128'");
  EXPECT_EQ(err(kMaestro + ", multiple_targets: 1"),
            "RIG:4:88: rig.buses[0].multiple_targets: expected true or false, found '1'");
  EXPECT_EQ(err(kMaestro + ", response_timeout_ms: 50, fault_after_ms: 40"),
            "RIG:4:111: rig.buses[0].fault_after_ms: expected fault_after_ms above "
            "response_timeout_ms (50 ms), found 40 ms");
  EXPECT_EQ(err(kMaestro + ", watchdog_ms: 100"),
            "RIG:4:70: rig.buses[0].watchdog_ms: expected one of: name, type, device, baud, "
            "protocol, device_number, multiple_targets, cycle_ms, response_timeout_ms, "
            "fault_after_ms, reconnect_ms, found unknown key 'watchdog_ms'");
  EXPECT_EQ(err("type: maestro, device: \"\", baud: 115200"),
            "RIG:4:42: rig.buses[0].device: expected a serial device such as /dev/ttyACM0, "
            "found \"\"");
}

TEST(RigEncoding, MaestroChannelsTakeAMicrosecondPulseOf14Bits) {
  const std::string none = encoded_rig(kMaestro, "");
  EXPECT_TRUE(contains(budget_error(none),
                       "expected raw uint16 on Maestro bus b0 (the pulse width in µs), found no "
                       "encoding"))
      << budget_error(none);
  EXPECT_EQ(budget_error(encoded_rig(kMaestro, kServoUs)), "ok");
  // 300 us per degree: -6 deg is -300 us.
  const std::string wide = encoded_rig(kMaestro, "{ raw: int16, scale: 300, offset: 1500 }");
  EXPECT_EQ(budget_error(wide), at(wide) +
                                    ": actuator a1 encoding: expected raw uint16 on Maestro bus "
                                    "b0 (the pulse width in µs), found raw int16");
  const std::string far = encoded_rig(kMaestro, "{ raw: uint16, scale: 200, offset: 1500 }");
  EXPECT_EQ(budget_error(far), at(far) +
                                   ": actuator a1 encoding: expected pulses within 1..4095 µs (a "
                                   "14-bit target in quarter-µs) on bus b0, found position 20 deg "
                                   "giving 5500 µs");
  // Ten channels at 115200 baud: 10 Set Target (40 bytes), 10 Get Position
  // (20 + 20 back), Get Errors (1 + 2 back): 83 bytes; one Set Multiple
  // Targets instead: 23 bytes, 66 in all.
  std::vector<BusBudgetResult> results;
  EXPECT_EQ(budget_error(pca_rig(kMaestro, 10), 1000.0, &results), "ok");
  EXPECT_EQ(results.at(0).text,
            "b0: 10 Maestro channels, 83 bytes per I/O cycle = 7.20 ms at 115200 baud, 36% of "
            "the 20 ms cycle");
  EXPECT_EQ(budget_error(pca_rig(kMaestro + ", multiple_targets: true", 10), 1000.0, &results),
            "ok");
  EXPECT_EQ(results.at(0).text,
            "b0: 10 Maestro channels, 66 bytes per I/O cycle = 5.73 ms at 115200 baud, 29% of "
            "the 20 ms cycle");
  // Channel 24 is beyond the largest Maestro.
  const std::string many = budget_error(pca_rig(kMaestro, 24));
  EXPECT_TRUE(contains(many,
                       "rig.actuators 'a24'.address: expected a channel 0..23 on Maestro bus b0, "
                       "found 24"))
      << many;
}

}  // namespace
}  // namespace facectl
