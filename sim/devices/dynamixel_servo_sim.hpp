#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace facectl::sim {

// One DYNAMIXEL X-series servo as its e-Manual describes it (XL430-W250 by
// default): the control table with its EEPROM/RAM access rules, Protocol
// 2.0's instructions (ping, read, write, sync read, sync write, reboot), the
// Status Return Level, the Bus Watchdog, Hardware Error Status with the
// alert bit, and a first-order motor. Not thread-safe: DynamixelPtyWire
// serialises every call.
class DynamixelServoSim {
 public:
  explicit DynamixelServoSim(std::uint8_t id, std::uint16_t model = 1060,
                             std::int32_t position = 2048);

  std::uint8_t id() const { return table_[7]; }
  // One instruction packet's content, at `now_ns`: appends the status packet
  // (if any) to `reply`. Sync read returns this servo's part only.
  void handle(std::uint8_t target_id, std::uint8_t instruction,
              std::span<const std::uint8_t> params, std::int64_t now_ns,
              std::vector<std::uint8_t>& reply);

  // Test access.
  std::uint8_t byte(std::uint16_t address) const { return table_.at(address); }
  std::int32_t goal() const;
  std::int32_t present() const;
  bool torque() const { return table_[64] != 0; }
  // Sets Hardware Error Status: the servo marks every status packet with the
  // alert bit until rebooted, and switches its torque off if a bit is in its
  // Shutdown item (63; the factory's 0x34: overload, shock, overheating).
  void raise_hardware_error(std::uint8_t bits);
  void set_temperature(std::uint8_t celsius) { table_[146] = celsius; }
  // Turns the horn by hand (torque off): the servo now stands at `pulses`.
  void move_by_hand(std::int32_t pulses);
  // As if no instruction had come for the Bus Watchdog's period.
  void trip_bus_watchdog() { table_[98] = 0xFF; }
  void set_load_permille(std::int16_t load);
  std::uint64_t eeprom_writes() const { return eeprom_writes_; }
  std::uint64_t instructions() const { return instructions_; }

 private:
  void advance(std::int64_t now_ns);
  std::uint8_t write(std::uint16_t address, std::span<const std::uint8_t> data,
                     std::int64_t now_ns);
  void status(std::uint8_t error, std::span<const std::uint8_t> params,
              std::vector<std::uint8_t>& reply) const;
  void reset_ram();

  std::array<std::uint8_t, 256> table_{};
  double position_ = 2048.0;  // pulses, continuous
  std::int64_t last_ns_ = -1;
  std::int64_t last_instruction_ns_ = 0;
  std::uint64_t eeprom_writes_ = 0;
  std::uint64_t instructions_ = 0;
};

}  // namespace facectl::sim
