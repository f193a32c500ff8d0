#include "drivers/protocol/feetech_table.hpp"

#include "drivers/protocol/feetech_packet.hpp"

namespace facectl::ft {

const char* error_text(std::uint8_t bit) {
  switch (bit) {
    case kErrVoltage:
      return "input voltage";
    case kErrAngle:
      return "angle sensor";
    case kErrOverheat:
      return "overheating";
    case kErrOverCurrent:
      return "overcurrent";
    case kErrOverload:
      return "overload";
    default:
      return "unknown bit";
  }
}

std::size_t cycle_bytes(Series s, std::size_t servos) {
  const std::size_t write = scs::kOverhead + 2 + servos * 3;
  const std::size_t replies = servos * (scs::kOverhead + kFeedbackLength);
  const std::size_t reads =
      s == Series::kSts ? scs::kOverhead + 2 + servos : servos * (scs::kOverhead + 2);
  return write + reads + replies;
}

}  // namespace facectl::ft
