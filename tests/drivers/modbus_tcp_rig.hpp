#pragma once

#include <string>

#include "tests/support/temp_file.hpp"

namespace facectl::testing {

// A runtime file on the shipped head and expressions, with a rig of three
// jaw actuators on one Modbus TCP bus at 127.0.0.1:`port` (one board, unit 1,
// channels 0..2; with `board_2`, a neck servo on unit 2 too), and a
// safety_io block on `chip`. For driving a simulated board server through the
// real configuration path.
struct ModbusTcpRig {
  // `bus_keys` are added to the bus entry (", key: value, ...").
  explicit ModbusTcpRig(int port, const std::string& chip = "sim", bool board_2 = false,
                        const std::string& bus_keys = "")
      : rig(rig_text(port, board_2, bus_keys)), runtime(runtime_text(rig.path(), chip)) {}

  static std::string rig_text(int port, bool board_2, const std::string& bus_keys) {
    std::string s =
        "rig:\n  name: tcp\n  buses:\n    - { name: modbus0, type: modbus_tcp, host: "
        "127.0.0.1:" +
        std::to_string(port) + ", response_timeout_ms: 20, retries: 1, fault_after_ms: 100" +
        bus_keys + " }\n  actuators:\n";
    const char* names[] = {"jaw_pitch", "jaw_yaw", "jaw_protrusion"};
    const char* signals[] = {"jaw_pitch_deg", "jaw_yaw_deg", "jaw_protrusion_mm"};
    for (int i = 0; i < 3; ++i) {
      const bool linear = i == 2;
      const std::string u = linear ? "mm" : "deg";
      s += "    - { name: " + std::string(names[i]) + ", kind: " + (linear ? "linear" : "rotary") +
           ", bus: modbus0, address: " + std::to_string(i + 1) + ", position_" + u +
           ": { min: -8, max: 20 }, max_velocity_" + u + "_s: 100, max_acceleration_" + u +
           "_s2: 2000, rest_" + u + ": 0, map: { terms: { " + signals[i] + ": 1 } } }\n";
    }
    if (board_2) {
      s += "    - { name: neck_pan, kind: rotary, bus: modbus0, address: 9, position_deg: { min: "
           "-60, max: 60 }, max_velocity_deg_s: 100, max_acceleration_deg_s2: 2000, rest_deg: 0, "
           "map: { terms: { neck_pan_deg: 1 } } }\n";
    }
    return s;
  }
  static std::string runtime_text(const std::string& rig_path, const std::string& chip) {
    const std::string dir = std::string(FACECTL_SOURCE_DIR) + "/config/";
    return "runtime: { realtime: { priority: 0, cpu: -1, lock_memory: false, "
           "cpu_dma_latency_us: -1 } }\nhead: " +
           dir + "heads/default/head.yaml\nrig: " + rig_path + "\nexpressions: " + dir +
           "expressions/library.yaml\nshow: " + dir +
           "shows/demo.yaml\nhardware: real\nsafety_io: { chip: " + chip +
           ", estop_line: 3, power_line: 4, release_debounce_ms: 5 }\n";
  }

  TempFile rig;
  TempFile runtime;
};

}  // namespace facectl::testing
