#include "sim/devices/dynamixel_servo_sim.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/protocol/dynamixel2_packet.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"

namespace facectl::sim {
namespace {

namespace x = dxl_x;
using dxl2::ResultError;

constexpr double kTimeConstantS = 0.03;  // the motor's response, first order
constexpr std::uint16_t kTableSize = 256;
constexpr std::uint16_t kShutdown = 63;  // which Hardware Error bits switch the torque off

// The e-Manual's Access column: R items a write must not touch.
bool read_only(std::uint16_t a) {
  return a < 7 || a == 69 || a == 70 || (a >= 120 && a < 148);
}

std::uint8_t error_byte(ResultError e) {
  return static_cast<std::uint8_t>(e);
}

}  // namespace

DynamixelServoSim::DynamixelServoSim(std::uint8_t id, std::uint16_t model, std::int32_t position)
    : position_(position) {
  x::put_u16(&table_[x::kModelNumber], model);
  table_[x::kFirmwareVersion] = 46;
  table_[7] = id;
  table_[8] = 1;                      // 57600 baud
  table_[x::kReturnDelayTime] = 250;  // 500 us, the factory setting
  table_[x::kOperatingMode] = x::kPositionControlMode;
  table_[x::kTemperatureLimit] = 72;
  table_[kShutdown] = 0x34;  // overload, electrical shock, overheating: the factory's
  x::put_i32(&table_[x::kMaxPositionLimit], 4095);
  x::put_i32(&table_[x::kMinPositionLimit], 0);
  reset_ram();
}

void DynamixelServoSim::reset_ram() {
  std::fill(table_.begin() + x::kTorqueEnable, table_.end(), 0);
  table_[x::kStatusReturnLevel] = 2;
  table_[x::kPresentTemperature] = 28;
  x::put_u16(&table_[x::kPresentInputVoltage], 120);
  x::put_i32(&table_[x::kGoalPosition], static_cast<std::int32_t>(std::lround(position_)));
  x::put_i32(&table_[x::kPresentPosition], static_cast<std::int32_t>(std::lround(position_)));
}

std::int32_t DynamixelServoSim::goal() const {
  return x::get_i32(&table_[x::kGoalPosition]);
}
std::int32_t DynamixelServoSim::present() const {
  return x::get_i32(&table_[x::kPresentPosition]);
}

void DynamixelServoSim::raise_hardware_error(std::uint8_t bits) {
  table_[x::kHardwareErrorStatus] = bits;
  if ((bits & table_[kShutdown]) != 0) table_[x::kTorqueEnable] = 0;
}

void DynamixelServoSim::move_by_hand(std::int32_t pulses) {
  position_ = pulses;
  x::put_i32(&table_[x::kPresentPosition], pulses);
}

void DynamixelServoSim::set_load_permille(std::int16_t load) {
  x::put_u16(&table_[x::kPresentLoad], static_cast<std::uint16_t>(load));
}

void DynamixelServoSim::advance(std::int64_t now_ns) {
  if (last_ns_ >= 0 && now_ns > last_ns_) {
    const double dt = static_cast<double>(now_ns - last_ns_) * 1e-9;
    if (torque()) {
      position_ += (goal() - position_) * (1.0 - std::exp(-dt / kTimeConstantS));
    }
    // The Bus Watchdog: torque on and no instruction for its period stops
    // the servo where it is and makes the goal read-only (value -1).
    const std::uint8_t watchdog = table_[x::kBusWatchdog];
    if (torque() && watchdog != 0 && watchdog != 0xFF &&
        now_ns - last_instruction_ns_ > watchdog * x::kBusWatchdogUnitMs * 1'000'000LL) {
      table_[x::kBusWatchdog] = 0xFF;
      x::put_i32(&table_[x::kGoalPosition], static_cast<std::int32_t>(std::lround(position_)));
    }
  }
  last_ns_ = now_ns;
  x::put_i32(&table_[x::kPresentPosition], static_cast<std::int32_t>(std::lround(position_)));
}

std::uint8_t DynamixelServoSim::write(std::uint16_t address, std::span<const std::uint8_t> data,
                                      std::int64_t now_ns) {
  if (data.empty() || address + data.size() > x::kTableEnd) {
    return error_byte(ResultError::kDataLength);
  }
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (read_only(static_cast<std::uint16_t>(address + i))) {
      return error_byte(ResultError::kAccess);
    }
  }
  // EEPROM is writable only with the torque off.
  if (address < x::kTorqueEnable) {
    if (torque()) return error_byte(ResultError::kAccess);
    ++eeprom_writes_;
  }
  const auto covers = [&](std::uint16_t a, std::size_t n) {
    return address <= a && a + n <= address + data.size();
  };
  if (covers(x::kGoalPosition, 4)) {
    const std::int32_t goal = x::get_i32(&data[x::kGoalPosition - address]);
    if (table_[x::kBusWatchdog] == 0xFF || goal < x::get_i32(&table_[x::kMinPositionLimit]) ||
        goal > x::get_i32(&table_[x::kMaxPositionLimit])) {
      return error_byte(ResultError::kDataRange);
    }
  }
  if (covers(x::kTorqueEnable, 1) && data[x::kTorqueEnable - address] > 1) {
    return error_byte(ResultError::kDataRange);
  }
  if (covers(x::kTorqueEnable, 1) && data[x::kTorqueEnable - address] == 1 &&
      table_[x::kHardwareErrorStatus] != 0) {
    return error_byte(ResultError::kResultFail);  // off until rebooted
  }
  std::copy(data.begin(), data.end(), table_.begin() + address);
  if (covers(x::kTorqueEnable, 1) && table_[x::kTorqueEnable] == 1) last_ns_ = now_ns;
  return 0;
}

void DynamixelServoSim::status(std::uint8_t error, std::span<const std::uint8_t> params,
                               std::vector<std::uint8_t>& reply) const {
  if (table_[x::kHardwareErrorStatus] != 0) error |= dxl2::kErrorAlert;
  std::uint8_t out[dxl2::max_packet_size(kTableSize + 1)];
  const std::size_t n = dxl2::encode_status(id(), error, params, out);
  reply.insert(reply.end(), out, out + n);
}

void DynamixelServoSim::handle(std::uint8_t target_id, std::uint8_t instruction,
                               std::span<const std::uint8_t> p, std::int64_t now_ns,
                               std::vector<std::uint8_t>& reply) {
  const bool mine = target_id == id();
  const bool broadcast = target_id == dxl2::kBroadcastId;
  if (!mine && !broadcast) return;
  ++instructions_;
  advance(now_ns);
  last_instruction_ns_ = now_ns;
  const std::uint8_t level = table_[x::kStatusReturnLevel];
  const auto u16 = [&](std::size_t at) { return x::get_u16(&p[at]); };
  switch (instruction) {
    case dxl2::kPing: {
      const std::uint8_t info[3] = {table_[0], table_[1], table_[x::kFirmwareVersion]};
      status(0, info, reply);  // PING is answered at every level
      return;
    }
    case dxl2::kRead: {
      if (!mine || level < 1) return;
      if (p.size() != 4) return status(error_byte(ResultError::kDataLength), {}, reply);
      const std::uint16_t a = u16(0), n = u16(2);
      if (a + n > kTableSize) return status(error_byte(ResultError::kDataRange), {}, reply);
      return status(0, {&table_[a], n}, reply);
    }
    case dxl2::kWrite: {
      if (p.size() < 3) {
        if (mine && level == 2) status(error_byte(ResultError::kDataLength), {}, reply);
        return;
      }
      const std::uint8_t e = write(u16(0), p.subspan(2), now_ns);
      if (mine && table_[x::kStatusReturnLevel] == 2) status(e, {}, reply);
      return;
    }
    case dxl2::kReboot:
      position_ = present();
      table_[x::kHardwareErrorStatus] = 0;
      reset_ram();
      if (mine && level == 2) status(0, {}, reply);
      return;
    case dxl2::kSyncWrite:
    case dxl2::kSyncRead: {
      if (!broadcast || p.size() < 4) return;
      const std::uint16_t a = u16(0), n = u16(2);
      const std::size_t stride = instruction == dxl2::kSyncWrite ? 1U + n : 1U;
      for (std::size_t at = 4; at + stride <= p.size(); at += stride) {
        if (p[at] != id()) continue;
        if (instruction == dxl2::kSyncWrite) {
          write(a, p.subspan(at + 1, n), now_ns);  // no status packet: errors are lost
        } else if (a + n <= kTableSize) {
          status(0, {&table_[a], n}, reply);
        } else {
          status(error_byte(ResultError::kDataRange), {}, reply);
        }
      }
      return;
    }
    default:
      if (mine && level == 2) status(error_byte(ResultError::kInstruction), {}, reply);
  }
}

}  // namespace facectl::sim
