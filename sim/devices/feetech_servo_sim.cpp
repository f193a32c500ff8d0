#include "sim/devices/feetech_servo_sim.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/protocol/feetech_packet.hpp"

namespace facectl::sim {
namespace {

constexpr double kTimeConstantS = 0.03;  // the motor's response, first order

// Read-only items of the memory table: firmware and model (0..4), and the
// present values from 56 up.
bool read_only(unsigned a) {
  return a < ft::kId || a >= ft::kPresentPosition;
}

}  // namespace

FeetechServoSim::FeetechServoSim(std::uint8_t id, ft::Series series, std::int32_t position)
    : series_(series) {
  const int steps = ft::steps_per_turn(series);
  position_ = position >= 0 ? position : steps / 2;
  // Illustrative model numbers: facectl does not check them.
  ft::put_u16(series_, &table_[ft::kModel], series == ft::Series::kSts ? 777 : 1284);
  table_[ft::kId] = id;
  table_[ft::kReturnDelay] = 0;
  table_[ft::kResponseLevel] = 1;
  ft::put_u16(series_, &table_[ft::kMinAngleLimit], 0);
  ft::put_u16(series_, &table_[ft::kMaxAngleLimit], static_cast<std::uint16_t>(steps - 1));
  std::copy_n(table_.begin(), saved_.size(), saved_.begin());
  reset_ram();
}

void FeetechServoSim::reset_ram() {
  std::fill(table_.begin() + ft::kTorqueEnable, table_.end(), 0);
  table_[ft::lock_address(series_)] = 1;
  table_[ft::kPresentTemperature] = 27;
  table_[ft::kPresentVoltage] = 74;  // 7.4 V
  const auto at = static_cast<std::uint16_t>(std::lround(position_));
  ft::put_u16(series_, &table_[ft::kGoalPosition], at);
  ft::put_u16(series_, &table_[ft::kPresentPosition], at);
}

void FeetechServoSim::power_cycle() {
  std::copy(saved_.begin(), saved_.end(), table_.begin());
  error_ = 0;
  last_ns_ = -1;
  reset_ram();
}

void FeetechServoSim::raise_error(std::uint8_t bits) {
  error_ = bits;
  if ((bits & (ft::kErrOverload | ft::kErrOverCurrent | ft::kErrOverheat)) != 0) {
    table_[ft::kTorqueEnable] = 0;
  }
}

void FeetechServoSim::set_load_permille(int load) {
  ft::put_u16(series_, &table_[ft::kPresentLoad], ft::to_sign_magnitude(load, 10));
}

void FeetechServoSim::move_by_hand(std::int32_t steps) {
  position_ = steps;
  ft::put_u16(series_, &table_[ft::kPresentPosition], static_cast<std::uint16_t>(steps));
}

void FeetechServoSim::advance(std::int64_t now_ns) {
  if (last_ns_ >= 0 && now_ns > last_ns_ && torque()) {
    const double dt = static_cast<double>(now_ns - last_ns_) * 1e-9;
    position_ += (goal() - position_) * (1.0 - std::exp(-dt / kTimeConstantS));
  }
  last_ns_ = now_ns;
  ft::put_u16(series_, &table_[ft::kPresentPosition],
              static_cast<std::uint16_t>(std::lround(position_)));
}

void FeetechServoSim::write(std::uint8_t address, std::span<const std::uint8_t> data) {
  if (data.empty() || address + data.size() > ft::kTableEnd) return;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const unsigned a = address + static_cast<unsigned>(i);
    if (read_only(a)) continue;  // the servo ignores what it cannot take
    table_[a] = data[i];
    // EEPROM keeps a value over a power cycle only if written unlocked.
    if (a < ft::kTorqueEnable && table_[ft::lock_address(series_)] == 0) {
      saved_[a] = data[i];
      ++eeprom_writes_;
    }
  }
  // A goal beyond the angle limits is taken as the limit.
  const int lo = word(ft::kMinAngleLimit);
  const int hi = word(ft::kMaxAngleLimit);
  const int g = std::clamp(static_cast<int>(word(ft::kGoalPosition)), lo, std::max(lo, hi));
  ft::put_u16(series_, &table_[ft::kGoalPosition], static_cast<std::uint16_t>(g));
}

void FeetechServoSim::handle(std::uint8_t target_id, std::uint8_t instruction,
                             std::span<const std::uint8_t> params, std::int64_t now_ns,
                             std::vector<std::uint8_t>& reply) {
  advance(now_ns);
  const bool broadcast = target_id == scs::kBroadcastId;
  if (!broadcast && target_id != id()) return;
  std::vector<std::uint8_t> data;
  bool answer = !broadcast;
  switch (instruction) {
    case scs::kPing:
      break;
    case scs::kRead: {
      if (params.size() != 2 || params[0] + params[1] > ft::kTableEnd) return;
      data.assign(table_.begin() + params[0], table_.begin() + params[0] + params[1]);
      break;
    }
    case scs::kWrite:
      if (params.empty()) return;
      write(params[0], params.subspan(1));
      answer = answer && table_[ft::kResponseLevel] != 0;
      break;
    case scs::kRegWrite:
      if (params.empty()) return;
      registered_.assign(params.begin(), params.end());
      answer = answer && table_[ft::kResponseLevel] != 0;
      break;
    case scs::kAction:
      if (!registered_.empty()) {
        write(registered_[0], std::span<const std::uint8_t>(registered_).subspan(1));
      }
      registered_.clear();
      answer = answer && table_[ft::kResponseLevel] != 0;
      break;
    case scs::kSyncWrite: {
      // address, length, then (id, length bytes) per servo; no reply.
      if (params.size() < 2 || params[1] == 0) return;
      const std::size_t step = 1u + params[1];
      for (std::size_t k = 2; k + step <= params.size(); k += step) {
        if (params[k] == id()) write(params[0], params.subspan(k + 1, params[1]));
      }
      return;
    }
    case scs::kSyncRead: {
      // SCS servos do not know it: silence, as the SCS0009 gives.
      if (series_ != ft::Series::kSts || params.size() < 2) return;
      if (std::find(params.begin() + 2, params.end(), id()) == params.end()) return;
      if (params[0] + params[1] > ft::kTableEnd) return;
      data.assign(table_.begin() + params[0], table_.begin() + params[0] + params[1]);
      answer = true;
      break;
    }
    default:
      return;
  }
  if (!answer) return;
  std::vector<std::uint8_t> out(scs::kOverhead + data.size());
  out.resize(scs::encode_status(id(), error_, data, out));
  reply.insert(reply.end(), out.begin(), out.end());
}

}  // namespace facectl::sim
