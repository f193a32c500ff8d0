// HID report descriptors (docs/PROTOCOLS.md, "HID gamepad"): any bytes are
// parsed as a device's descriptor, as HidGamepad does at each open; a
// descriptor it accepts yields a layout validate() accepts, and then the rest
// of the input as a report decodes to axes within -1..1.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "drivers/hid/gamepad_descriptor_layout.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl;
  if (size < 2) return 0;
  // The first two bytes (little-endian) say how much of the rest is the
  // descriptor (scripts/fuzz.sh seeds it with the real ones so).
  const std::size_t n = std::min<std::size_t>(size - 2, data[0] | data[1] << 8);
  const std::span<const std::uint8_t> descriptor(data + 2, n);
  const std::span<const std::uint8_t> report(data + 2 + n, size - 2 - n);
  GamepadLayout layout;
  try {
    layout = gamepad_layout_from_descriptor(descriptor);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  validate(layout);  // throws (and so fails the run) if the layout made is bad
  GamepadState state;
  if (decode_gamepad_report(layout, report, state)) {
    for (std::size_t i = 0; i < layout.axes.size(); ++i) {
      if (!(std::fabs(state.axes[i]) <= 1.0)) std::abort();
    }
  }
  return 0;
}
