#include "drivers/modbus/modbus_timeouts.hpp"

#include <cmath>
#include <cstdint>

namespace facectl {
namespace {

void split_seconds(double s, std::uint32_t& sec, std::uint32_t& usec) {
  const auto us = static_cast<std::uint64_t>(std::llround(s * 1e6));
  sec = static_cast<std::uint32_t>(us / 1'000'000);
  usec = static_cast<std::uint32_t>(us % 1'000'000);
}

}  // namespace

void set_modbus_timeouts(modbus_t* ctx, const ModbusTiming& timing) {
  std::uint32_t sec = 0;
  std::uint32_t usec = 0;
  split_seconds(timing.response_timeout_s, sec, usec);
  modbus_set_response_timeout(ctx, sec, usec);
  split_seconds(timing.byte_timeout_s, sec, usec);
  modbus_set_byte_timeout(ctx, sec, usec);
}

}  // namespace facectl
