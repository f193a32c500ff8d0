#pragma once

#include <cstdint>
#include <span>

namespace facectl {

// One edge of an input line, in logical terms (after the line's active level).
struct GpioEdge {
  bool active = false;  // the line became active (true) or inactive (false)
};

// The GPIO chip interface the safety I/O needs: a few lines, requested once,
// then read and written without blocking from the real-time tick. GpiodChip is
// the real one (libgpiod v1); SimGpioChip is its in-process twin.
class GpioChip {
 public:
  virtual ~GpioChip() = default;
  // Request a line; returns a handle. Throws std::runtime_error naming the
  // chip and the offset when the line cannot be had.
  virtual int request_input(unsigned offset, bool active_low, const char* consumer) = 0;
  virtual int request_output(unsigned offset, bool active_low, bool initial,
                             const char* consumer) = 0;
  // Non-blocking: the edges queued since the last call (at most out.size()),
  // 0 when none, -1 when the line can no longer be read.
  virtual int read_edges(int handle, std::span<GpioEdge> out) = 0;
  // Logical value: 1 active, 0 inactive, -1 on error.
  virtual int get_value(int handle) = 0;
  virtual bool set_value(int handle, bool active) = 0;
};

}  // namespace facectl
