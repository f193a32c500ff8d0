#pragma once

#include "drivers/protocol/can_frame.hpp"

namespace facectl {

// What an error frame (or the controller's state) says about the bus.
enum class CanError {
  kNone,
  kBusOff,        // the controller left the bus: nothing gets through
  kErrorPassive,  // TX or RX error counter above 127
  kNoAck,         // nobody acknowledged our frames
  kProtocol,      // bit, stuff, form or CRC errors on the wire
  kWarning,       // error counter above 96: counted, not a fault
  kOverflow,      // a receive buffer overflowed: counted, not a fault
  kRestarted,     // the controller came back from bus-off
};
const char* to_string(CanError e);

// A raw CAN endpoint. Both calls are non-blocking, so the real-time tick may
// make them: send() refuses a frame when the TX queue is full, receive()
// returns false when nothing is waiting.
class CanTransport {
 public:
  virtual ~CanTransport() = default;
  virtual bool send(const CanFrame& frame) = 0;
  // A data frame (error == kNone) or an error frame (error set, frame unused).
  virtual bool receive(CanFrame& frame, CanError& error) = 0;
};

}  // namespace facectl
