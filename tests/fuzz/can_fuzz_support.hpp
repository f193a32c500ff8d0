// Drives a CAN actuator bus (CustomCanBus, Cia402Bus) with frames from a fuzz
// input: the bus reads them from a CanTransport exactly as it reads SocketCAN
// in the tick, between its own writes, enables and status queries.
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <cmath>
#include <deque>
#include <vector>

#include "control/actuator_bus.hpp"
#include "drivers/can/can_bus_options.hpp"
#include "drivers/can/can_transport.hpp"

namespace facectl::fuzz {

// Frames and error frames queued by the input; send() takes everything until
// the input says the TX queue is full.
class ScriptedCanTransport final : public CanTransport {
 public:
  struct Rx {
    CanFrame frame;
    CanError error = CanError::kNone;
  };
  bool send(const CanFrame&) override { return !tx_full; }
  bool receive(CanFrame& frame, CanError& error) override {
    if (rx.empty()) return false;
    frame = rx.front().frame;
    error = rx.front().error;
    rx.pop_front();
    return true;
  }
  std::deque<Rx> rx;
  bool tx_full = false;
};

// A frame as a driver may receive it: an identifier aimed at one of `bases`
// plus a node (the replies a driver waits for) or any 11-bit one, and up to 8
// data bytes (64 for CAN FD), as SocketCAN delivers them.
inline CanFrame consume_frame(FuzzedDataProvider& in, const std::vector<std::uint32_t>& bases) {
  CanFrame f;
  if (!bases.empty() && in.ConsumeBool()) {
    f.id = bases[in.ConsumeIntegralInRange<std::size_t>(0, bases.size() - 1)] +
           in.ConsumeIntegralInRange<std::uint32_t>(0, 127);
  } else {
    f.id = in.ConsumeIntegralInRange<std::uint32_t>(0, 0x7FF);
  }
  f.fd = in.ConsumeBool();
  f.len = in.ConsumeIntegralInRange<std::uint8_t>(0, f.fd ? 64 : 8);
  for (std::size_t i = 0; i < f.len; ++i) f.data[i] = in.ConsumeIntegral<std::uint8_t>();
  return f;
}

// Rotary or linear actuators on the addresses the input picks, each with the
// input's wire encoding (what a rig file can state).
inline std::vector<ActuatorModel> consume_actuators(FuzzedDataProvider& in, int max_address) {
  std::vector<ActuatorModel> actuators(in.ConsumeIntegralInRange<std::size_t>(1, 8));
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    ActuatorModel& a = actuators[i];
    a.name = "a" + std::to_string(i);
    a.address = in.ConsumeIntegralInRange(1, max_address);
    a.kind = in.ConsumeBool() ? ActuatorKind::kRotary : ActuatorKind::kLinear;
    a.limits.position_min = -0.5;
    a.limits.position_max = 0.5;
    a.limits.max_velocity = 3.0;
    a.encoding.raw = static_cast<ActuatorEncoding::Raw>(in.ConsumeIntegralInRange(0, 2));
    // The rig loader's rules: any finite scale but 0, any finite offset.
    if (in.ConsumeBool()) {
      const double scale = in.ConsumeFloatingPoint<double>();
      if (std::isfinite(scale) && scale != 0.0) a.encoding.scale = scale;
      const double offset = in.ConsumeFloatingPoint<double>();
      if (std::isfinite(offset)) a.encoding.offset = offset;
    }
  }
  return actuators;
}

// Runs the bus through ticks chosen by the input until it is used up.
inline void run_bus(FuzzedDataProvider& in, ActuatorBus& bus, ScriptedCanTransport& link,
                    std::size_t count, const std::vector<std::uint32_t>& reply_bases) {
  TickTime time{1'000'000'000, 0.001};
  std::vector<double> positions(count), targets(count);
  std::vector<std::uint8_t> enabled(count);
  while (in.remaining_bytes() > 0) {
    switch (in.ConsumeIntegralInRange(0, 7)) {
      case 0:
        link.rx.push_back({consume_frame(in, reply_bases), CanError::kNone});
        break;
      case 1:
        link.rx.push_back({CanFrame{}, static_cast<CanError>(in.ConsumeIntegralInRange(1, 7))});
        break;
      case 2:
        bus.read(time, positions);
        break;
      case 3:
        for (double& t : targets) t = in.ConsumeFloatingPointInRange(-1.0, 1.0);
        bus.write(time, targets);
        break;
      case 4:
        bus.set_enabled(in.ConsumeBool());
        break;
      case 5:
        for (auto& e : enabled) e = in.ConsumeBool() ? 1 : 0;
        bus.set_actuators_enabled(enabled);
        break;
      case 6:
        link.tx_full = in.ConsumeBool();
        break;
      default:
        time.now_ns += in.ConsumeIntegralInRange<std::int64_t>(0, 300'000'000);
        break;
    }
    bus.status();
  }
}

}  // namespace facectl::fuzz
