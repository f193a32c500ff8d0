#include "drivers/can_bus_budget.hpp"

#include <cstdio>

namespace facectl {

CanBusBudget CanBusBudget::compute(int frames_per_cycle, double cycle_hz, long bitrate) {
  CanBusBudget b;
  b.frames_per_cycle = frames_per_cycle;
  b.cycle_hz = cycle_hz;
  b.bitrate = bitrate;
  b.load = bitrate > 0 ? frames_per_cycle * kBitsPerFrame * cycle_hz / static_cast<double>(bitrate)
                       : 1e9;
  return b;
}

std::string CanBusBudget::describe(const std::string& bus) const {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "%s: %d frames per cycle at %g Hz = %.0f bit/s, %.1f%% of %ld bit/s%s", bus.c_str(),
                frames_per_cycle, cycle_hz, frames_per_cycle * kBitsPerFrame * cycle_hz,
                100.0 * load, bitrate,
                refused()  ? " (refused: above 70%)"
                : warned() ? " (warning: above 50%)"
                           : "");
  return buf;
}

}  // namespace facectl
