#include "sim/devices/dynamixel_pty_wire.hpp"

#include <cstring>

#include "control/clock.hpp"
#include "drivers/protocol/dynamixel2_packet.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"

namespace facectl::sim {

DynamixelPtyWire::DynamixelPtyWire(std::vector<std::unique_ptr<DynamixelServoSim>> servos)
    : servos_(std::move(servos)) {
  thread_ = std::thread([this] { run(); });
}

DynamixelPtyWire::~DynamixelPtyWire() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

std::uint64_t DynamixelPtyWire::requests_of(std::uint8_t instruction) const {
  return by_instruction_[instruction].load();
}

void DynamixelPtyWire::run() {
  std::vector<std::uint8_t> buf(8192);
  std::vector<std::uint8_t> params(8192);
  std::size_t len = 0;
  while (!stop_.load()) {
    const std::size_t n = pty_.read(buf.data() + len, buf.size() - len, 20);
    if (n == 0) continue;
    len += n;
    for (;;) {
      dxl2::Packet pk;
      const dxl2::ParseResult r = dxl2::parse_packet({buf.data(), len}, pk, params);
      if (r == dxl2::ParseResult::kIncomplete && pk.consumed == 0) break;
      std::vector<std::uint8_t> raw(buf.begin(), buf.begin() + static_cast<long>(pk.consumed));
      std::memmove(buf.data(), buf.data() + pk.consumed, len - pk.consumed);
      len -= pk.consumed;
      if (r == dxl2::ParseResult::kIncomplete) break;
      // A bad CRC is dropped without a word, as a servo does.
      if (r != dxl2::ParseResult::kOk || pk.instruction == dxl2::kStatus) continue;
      requests_.fetch_add(1);
      by_instruction_[pk.instruction].fetch_add(1);
      serve(pk.id, pk.instruction, {params.begin(), params.begin() + pk.param_count}, raw.data(),
            raw.size());
    }
    if (len == buf.size()) len = 0;
  }
}

void DynamixelPtyWire::serve(std::uint8_t id, std::uint8_t instruction,
                             const std::vector<std::uint8_t>& params, const std::uint8_t* raw,
                             std::size_t raw_size) {
  if (faults_.echo.load()) pty_.write_all(raw, raw_size);
  // Sync read: the servos answer in the order the request lists them.
  std::vector<std::uint8_t> order;
  if (instruction == dxl2::kSyncRead) {
    order.assign(params.begin() + std::min<std::size_t>(4, params.size()), params.end());
  } else {
    std::lock_guard lock(mutex_);
    for (auto& s : servos_) order.push_back(s->id());
  }
  for (const std::uint8_t target : order) {
    std::vector<std::uint8_t> reply;
    int delay_us = 0;
    {
      std::lock_guard lock(mutex_);
      for (auto& s : servos_) {
        if (s->id() != target) continue;
        s->handle(id, instruction, params, monotonic_ns(), reply);
        delay_us = 2 * s->byte(dxl_x::kReturnDelayTime);
      }
    }
    if (reply.empty() || faults_.mute_id.load() == target) continue;
    if (faults_.corrupt_next.load() > 0) {
      faults_.corrupt_next.fetch_sub(1);
      reply.back() ^= 0x5A;
    }
    sleep_us(delay_us + faults_.extra_delay_us.load());
    pty_.write_all(reply.data(), reply.size());
  }
}

}  // namespace facectl::sim
