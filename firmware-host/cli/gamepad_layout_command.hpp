#pragma once

#include <string>

namespace facectl {

struct GamepadLayoutOptions {
  std::string device;      // a hidraw path, or VENDOR:PRODUCT in hex
  std::string descriptor;  // or a report descriptor file (binary, or hex text)
};

// `facectl gamepad layout`: prints the layout a gamepad's report descriptor
// declares (axes and buttons with their byte, bit, width and range), the one
// a runtime file's `gamepad:` block without `axes` and `buttons` uses.
// Exit codes: 0 printed; 2 no device, unreadable or no gamepad descriptor.
int gamepad_layout_command(const GamepadLayoutOptions& options);

}  // namespace facectl
