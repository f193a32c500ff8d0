#include "sim/devices/maestro_sim.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drivers/protocol/maestro_serial.hpp"

namespace facectl::sim {

namespace m = facectl::maestro;

MaestroSim::MaestroSim(int channels, int device_number)
    : channels_(channels), device_number_(device_number) {
  if (channels != 6 && channels != 12 && channels != 18 && channels != 24) {
    throw std::invalid_argument("a Maestro has 6, 12, 18 or 24 channels");
  }
  min_q_.fill(992 * 4);  // the factory's servo range (Control Center, Channel Settings)
  max_q_.fill(2000 * 4);
}

void MaestroSim::set_range(int channel, int min_q, int max_q) {
  min_q_.at(static_cast<std::size_t>(channel)) = min_q;
  max_q_.at(static_cast<std::size_t>(channel)) = max_q;
}

int MaestroSim::position(int channel) const {
  return static_cast<int>(std::lround(positions_.at(static_cast<std::size_t>(channel))));
}

void MaestroSim::raise_error(std::uint16_t bits) {
  errors_ |= bits;
  go_home();
}

void MaestroSim::power_cycle() {
  go_home();
  errors_ = 0;
  stage_ = Stage::kIdle;
  data_.clear();
  last_ns_ = -1;
}

void MaestroSim::go_home() {
  targets_.fill(0);
  positions_.fill(0.0);
}

void MaestroSim::advance(std::int64_t now_ns) {
  if (last_ns_ < 0) last_command_ns_ = now_ns;
  if (last_ns_ >= 0) {
    const double dt = static_cast<double>(now_ns - last_ns_) * 1e-9;
    for (int c = 0; c < channels_; ++c) {
      const auto i = static_cast<std::size_t>(c);
      if (targets_[i] == 0 || positions_[i] == 0.0 || speeds_[i] == 0) {
        positions_[i] = targets_[i];
        continue;
      }
      // Speed: 0.25 µs per 10 ms, i.e. `speed` quarter-µs per 10 ms (5.e).
      const double step = speeds_[i] * dt / 0.010;
      const double d = targets_[i] - positions_[i];
      positions_[i] += std::clamp(d, -step, step);
    }
  }
  last_ns_ = now_ns;
  if (serial_timeout_ms_ > 0 && (errors_ & m::kErrSerialTimeout) == 0 &&
      now_ns - last_command_ns_ > static_cast<std::int64_t>(serial_timeout_ms_) * 1'000'000) {
    raise_error(m::kErrSerialTimeout);
  }
}

int MaestroSim::data_bytes_needed() const {
  switch (command_) {
    case m::kSetTarget:
    case m::kSetSpeed:
    case m::kSetAcceleration:
      return 3;
    case m::kGetPosition:
      return 1;
    case m::kGetErrors:
      return 0;
    case m::kSetMultipleTargets:
      return data_.empty() ? 1 : 2 + 2 * data_[0];
    default:
      return -1;
  }
}

void MaestroSim::feed(std::uint8_t byte, std::int64_t now_ns, std::vector<std::uint8_t>& reply) {
  advance(now_ns);
  if ((byte & 0x80) != 0) {
    // A command byte: an unfinished packet before it is a protocol error.
    if (stage_ == Stage::kDevice || stage_ == Stage::kCommand || stage_ == Stage::kData) {
      errors_ |= m::kErrSerialProtocol;
      go_home();
    }
    data_.clear();
    if (byte == m::kPololuStart) {
      stage_ = Stage::kDevice;
      return;
    }
    command_ = byte;
  } else {
    switch (stage_) {
      case Stage::kIdle:
        errors_ |= m::kErrSerialProtocol;  // a data byte with no command
        go_home();
        return;
      case Stage::kIgnore:
        return;  // a packet for another Pololu device
      case Stage::kDevice:
        stage_ = byte == device_number_ ? Stage::kCommand : Stage::kIgnore;
        return;
      case Stage::kCommand:
        command_ = static_cast<std::uint8_t>(byte | 0x80);  // MSB cleared on the wire
        break;
      case Stage::kData:
        data_.push_back(byte);
        break;
    }
  }
  // Set Multiple Targets exists on the Mini Maestros only.
  const bool known =
      data_bytes_needed() >= 0 && (command_ != m::kSetMultipleTargets || channels_ >= 12);
  if (!known) {
    errors_ |= m::kErrSerialProtocol;
    go_home();
    stage_ = Stage::kIgnore;
    return;
  }
  stage_ = Stage::kData;
  if (static_cast<int>(data_.size()) < data_bytes_needed()) return;
  stage_ = Stage::kIdle;
  execute(now_ns, reply);
}

void MaestroSim::execute(std::int64_t now_ns, std::vector<std::uint8_t>& reply) {
  const auto bad = [&] {
    errors_ |= m::kErrSerialProtocol;
    go_home();
  };
  const auto set_target = [&](int channel, int q) {
    const auto i = static_cast<std::size_t>(channel);
    targets_[i] = q == 0 ? 0 : std::clamp(q, min_q_[i], max_q_[i]);
    if (positions_[i] == 0.0) positions_[i] = targets_[i];  // from off: straight there
  };
  const auto u14 = [&](std::size_t at) { return data_[at] | (data_[at + 1] << 7); };
  ++counts_[command_];
  last_command_ns_ = now_ns;
  switch (command_) {
    case m::kSetTarget:
    case m::kSetSpeed:
    case m::kSetAcceleration: {
      const int channel = data_[0];
      if (channel >= channels_) return bad();
      const int v = u14(1);
      if (command_ == m::kSetTarget) set_target(channel, v);
      if (command_ == m::kSetSpeed) speeds_[static_cast<std::size_t>(channel)] = v;
      if (command_ == m::kSetAcceleration) accelerations_[static_cast<std::size_t>(channel)] = v;
      return;
    }
    case m::kSetMultipleTargets: {
      const int count = data_[0];
      const int first = data_[1];
      if (first + count > channels_) return bad();
      for (int k = 0; k < count; ++k)
        set_target(first + k, u14(2 + 2 * static_cast<std::size_t>(k)));
      return;
    }
    case m::kGetPosition: {
      if (data_[0] >= channels_) return bad();
      const int p = position(data_[0]);
      reply.push_back(static_cast<std::uint8_t>(p & 0xFF));
      reply.push_back(static_cast<std::uint8_t>(p >> 8));
      return;
    }
    case m::kGetErrors:
      reply.push_back(static_cast<std::uint8_t>(errors_ & 0xFF));
      reply.push_back(static_cast<std::uint8_t>(errors_ >> 8));
      errors_ = 0;
      return;
    default:
      return;
  }
}

}  // namespace facectl::sim
