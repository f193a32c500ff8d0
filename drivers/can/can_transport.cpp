#include "drivers/can/can_transport.hpp"

namespace facectl {

const char* to_string(CanError e) {
  switch (e) {
    case CanError::kNone:
      return "none";
    case CanError::kBusOff:
      return "bus-off";
    case CanError::kErrorPassive:
      return "error-passive";
    case CanError::kNoAck:
      return "no ACK";
    case CanError::kProtocol:
      return "protocol error";
    case CanError::kWarning:
      return "error warning";
    case CanError::kOverflow:
      return "RX overflow";
    case CanError::kRestarted:
      return "restarted";
  }
  return "?";
}

}  // namespace facectl
