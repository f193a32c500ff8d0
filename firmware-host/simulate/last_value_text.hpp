#pragma once

#include <bit>
#include <cstdint>
#include <cstring>

#include "firmware-host/simulate/write_g6.hpp"

namespace facectl {

// The %.6g text of a telemetry column's last value, reused while the value
// repeats: a held actuator repeats its command and position bit for bit row
// after row (about half of the non-zero values of the demo show), and copying
// their text costs a tenth of writing it again. The same bits give the same
// text, so the bytes do not change.
struct LastValueText {
  double value = 0.0;
  char text[16] = {'0'};
  std::uint8_t size = 1;

  // Writes v's text at p, which needs 16 bytes of room; returns the end.
  char* write(char* p, double v) {
    if (std::bit_cast<std::uint64_t>(v) != std::bit_cast<std::uint64_t>(value)) {
      size = static_cast<std::uint8_t>(write_g6(text, text + sizeof text, v) - text);
      value = v;
    }
    std::memcpy(p, text, sizeof text);  // a fixed-size copy; the bytes past `size` are scratch
    return p + size;
  }
};

}  // namespace facectl
