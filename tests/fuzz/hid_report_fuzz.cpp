// HID gamepad input reports (docs/PROTOCOLS.md, "HID gamepad"): a layout the
// input states, as a runtime file's `gamepad:` block can, kept only if
// validate() accepts it (as the config loader requires), then reports
// decoded with decode_gamepad_report, as the gamepad reader does.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "drivers/hid/gamepad_report.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl;
  FuzzedDataProvider in(data, size);
  GamepadLayout layout;
  layout.report_id = in.ConsumeIntegralInRange(-1, 255);
  layout.axes.resize(in.ConsumeIntegralInRange<std::size_t>(0, 17));
  for (auto& a : layout.axes) {
    a.byte = in.ConsumeIntegralInRange(-2, 70);
    a.bits = in.ConsumeBool() ? 8 : in.ConsumeIntegralInRange(0, 32);
    a.is_signed = in.ConsumeBool();
    a.min = in.ConsumeFloatingPoint<double>();
    a.max = in.ConsumeFloatingPoint<double>();
    a.bit = in.ConsumeIntegralInRange(-1, 8);
    a.kind = static_cast<GamepadLayout::Kind>(in.ConsumeIntegralInRange(0, 2));
    a.present = in.ConsumeBool();
  }
  layout.buttons.resize(in.ConsumeIntegralInRange<std::size_t>(0, 33));
  for (auto& b : layout.buttons) {
    b.byte = in.ConsumeIntegralInRange(-2, 70);
    b.bit = in.ConsumeIntegralInRange(-1, 9);
  }
  try {
    validate(layout);
  } catch (const std::invalid_argument&) {  // the loader refuses this layout
    return 0;
  }
  while (in.remaining_bytes() > 0) {
    const std::vector<std::uint8_t> report =
        in.ConsumeBytes<std::uint8_t>(in.ConsumeIntegralInRange<std::size_t>(0, 80));
    GamepadState state;
    if (decode_gamepad_report(layout, report, state)) {
      for (std::size_t i = 0; i < layout.axes.size(); ++i) {
        // Axes are documented as -1..1 (or NaN from a NaN min/max).
        if (std::fabs(state.axes[i]) > 1.0) std::abort();
      }
    }
  }
  return 0;
}
