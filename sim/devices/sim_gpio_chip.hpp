#pragma once

#include <array>
#include <atomic>
#include <mutex>
#include <vector>

#include "drivers/gpio/gpio_chip.hpp"

namespace facectl {

// The in-process twin of a GPIO chip. Tests drive input lines at their
// physical level (a pull-up e-stop pressed is low, or high: the requester's
// active level decides) and watch outputs; a line can vanish. Edges are queued
// like the kernel's, up to 64 per line. Thread-safe.
class SimGpioChip final : public GpioChip {
 public:
  explicit SimGpioChip(unsigned lines = 32);

  int request_input(unsigned offset, bool active_low, const char* consumer) override;
  int request_output(unsigned offset, bool active_low, bool initial, const char* consumer) override;
  int read_edges(int handle, std::span<GpioEdge> out) override;
  int get_value(int handle) override;
  bool set_value(int handle, bool active) override;

  void set_physical(unsigned offset, bool high);  // an input changes; queues an edge
  bool physical(unsigned offset) const;           // an output's level on the pin
  void remove_line(unsigned offset);              // the line vanishes (chip unplugged)

 private:
  struct Line {
    bool requested = false;
    bool output = false;
    bool active_low = false;
    bool high = false;
    bool gone = false;
    std::vector<GpioEdge> queue;
  };
  mutable std::mutex mutex_;
  std::vector<Line> lines_;
  std::vector<unsigned> handles_;
};

}  // namespace facectl
