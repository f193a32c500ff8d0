#pragma once

#include <string>

namespace facectl {

// The load a cyclic CAN schedule puts on the bus, with 135 bits as the worst
// case for a classic 8-byte frame (stuffing and interframe space included;
// reference/field-survey.md, part C). Every frame is budgeted at the worst
// case, whatever its length.
struct CanBusBudget {
  int frames_per_cycle = 0;
  double cycle_hz = 0.0;
  long bitrate = 0;
  double load = 0.0;  // fraction of the bitrate

  static constexpr double kBitsPerFrame = 135.0;
  static constexpr double kWarnLoad = 0.50;
  static constexpr double kRefuseLoad = 0.70;

  static CanBusBudget compute(int frames_per_cycle, double cycle_hz, long bitrate);
  bool refused() const { return load > kRefuseLoad; }
  bool warned() const { return load > kWarnLoad; }
  // "can0: 25 frames per cycle at 250 Hz = 843750 bit/s, 84.4% of 1000000 bit/s"
  std::string describe(const std::string& bus) const;
};

}  // namespace facectl
