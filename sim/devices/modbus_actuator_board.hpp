#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

#include "drivers/protocol/modbus_register_map.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl::sim {

struct BoardChannel {
  ServoPlantParams plant;
  modbus_map::Unit unit = modbus_map::Unit::kRotary;
  double initial = 0.0;       // SI
  ActuatorEncoding encoding;  // the rig actuator's, as the host's bus uses it
};

// The simulated Modbus actuator board behind docs/PROTOCOLS.md's register
// map: one ServoPlant per channel, a heartbeat watchdog that latches, and
// injectable board faults. Thread-safe: the server thread applies requests
// while a test reads positions and injects faults.
class ModbusActuatorBoard {
 public:
  ModbusActuatorBoard(int unit, std::vector<BoardChannel> channels);

  int unit() const { return unit_; }
  // Holding registers after a write at `now_ns` (the whole map, kHoldingCount).
  void apply_holding(std::int64_t now_ns, std::span<const std::uint16_t> holding,
                     bool targets_written);
  // Advances the plants and the watchdog to `now_ns` and fills the input
  // registers (kInputCount).
  void fill_inputs(std::int64_t now_ns, std::span<std::uint16_t> inputs);

  // Runs the board's own loop (plants, watchdog) up to `now_ns`, whether or
  // not any request arrives.
  void advance(std::int64_t now_ns);

  void inject_fault(modbus_map::FaultCode code);  // latched until a fault reset
  double position(std::size_t channel) const;     // true plant position, SI
  double target(std::size_t channel) const;       // last accepted target, SI
  bool enabled() const;
  bool watchdog_tripped() const;
  // Target writes accepted while enabled, and while disabled (a host must not
  // send targets while disabled: these count them).
  std::uint64_t target_writes() const { return target_writes_.load(); }
  std::uint64_t target_writes_while_disabled() const { return target_writes_disabled_.load(); }
  std::int64_t last_target_write_ns() const { return last_target_write_ns_.load(); }

 private:
  void step_locked(std::int64_t now_ns);

  const int unit_;
  mutable std::mutex mutex_;
  std::vector<BoardChannel> spec_;
  std::vector<WireEncoding> encodings_;
  std::vector<ServoPlant> plants_;
  std::vector<double> targets_;
  bool enabled_ = false;
  std::uint16_t heartbeat_ = 0;
  std::int64_t last_heartbeat_ns_ = 0;
  std::uint16_t watchdog_ms_ = 100;
  modbus_map::FaultCode fault_ = modbus_map::FaultCode::kNone;
  std::atomic<std::uint64_t> target_writes_{0};
  std::atomic<std::uint64_t> target_writes_disabled_{0};
  std::atomic<std::int64_t> last_target_write_ns_{0};
};

}  // namespace facectl::sim
