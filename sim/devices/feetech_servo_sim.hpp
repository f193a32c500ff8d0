#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "drivers/protocol/feetech_table.hpp"

namespace facectl::sim {

// One Feetech servo as its memory table describes it: an STS3215 (STS
// series, little-endian, 4096 steps) or an SCS0009 (SCS series, big-endian,
// 1024 steps). The table's access rules (read-only model and present
// values; EEPROM kept over a power cycle only while Lock is open), the
// instructions PING, READ, WRITE, REG_WRITE/ACTION, SYNC_WRITE and, on STS
// only, SYNC_READ; the Response Level, the error byte of every status
// packet, and a first-order motor. Not thread-safe: FeetechPtyWire
// serialises every call.
class FeetechServoSim {
 public:
  FeetechServoSim(std::uint8_t id, ft::Series series, std::int32_t position = -1);

  std::uint8_t id() const { return table_[ft::kId]; }
  ft::Series series() const { return series_; }
  // One instruction packet's content, at `now_ns`: appends the status packet
  // (if any) to `reply`. Sync read returns this servo's part only.
  void handle(std::uint8_t target_id, std::uint8_t instruction,
              std::span<const std::uint8_t> params, std::int64_t now_ns,
              std::vector<std::uint8_t>& reply);

  // Test access.
  std::uint8_t byte(std::uint8_t address) const { return table_.at(address); }
  std::uint16_t word(std::uint8_t address) const {
    return ft::get_u16(series_, &table_.at(address));
  }
  std::int32_t goal() const { return word(ft::kGoalPosition); }
  std::int32_t present() const { return word(ft::kPresentPosition); }
  bool torque() const { return table_[ft::kTorqueEnable] != 0; }
  // Sets the protection flags that every status packet carries; overload,
  // overcurrent and overheating also unload the torque, as the servo does.
  void raise_error(std::uint8_t bits);
  void set_temperature(std::uint8_t celsius) { table_[ft::kPresentTemperature] = celsius; }
  void set_load_permille(int load);  // sign-magnitude, bit 10
  void move_by_hand(std::int32_t steps);
  // Power off and on: RAM to defaults, EEPROM from what was saved unlocked.
  void power_cycle();
  std::uint64_t eeprom_writes() const { return eeprom_writes_; }

 private:
  void advance(std::int64_t now_ns);
  void write(std::uint8_t address, std::span<const std::uint8_t> data);
  void reset_ram();

  ft::Series series_;
  std::array<std::uint8_t, 256> table_{};
  std::array<std::uint8_t, ft::kTorqueEnable> saved_{};  // EEPROM as stored
  std::vector<std::uint8_t> registered_;                 // REG_WRITE: address, data
  double position_ = 0.0;
  std::int64_t last_ns_ = -1;
  std::uint8_t error_ = 0;
  std::uint64_t eeprom_writes_ = 0;
};

}  // namespace facectl::sim
