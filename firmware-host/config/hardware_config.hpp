#pragma once

#include <optional>
#include <string>
#include <vector>

#include "control/command/face_layout.hpp"
#include "drivers/gpio/gpio_safety_io.hpp"
#include "drivers/hid/gamepad_mapping.hpp"
#include "drivers/hid/gamepad_report.hpp"
#include "drivers/hid/hid_gamepad.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// Which hardware `facectl run` drives: the simulated twins (the default) or
// the real buses and GPIO named by the rig and the runtime file.
enum class HardwareMode { kSim, kReal };

// The runtime file's `safety_io:` block: the e-stop input, the power-enable
// output and an optional status LED on one GPIO chip (docs/CONFIG.md).
struct SafetyIoConfig {
  std::string chip = "gpiochip0";
  GpioSafetyConfig gpio;
  std::string where;
};

// The runtime file's `gamepad:` block: which device, where its axes and
// buttons sit in the report, and how they map onto face signals.
struct GamepadConfig {
  HidSelector selector;
  GamepadLayout layout;
  double rate_hz = 250.0;          // puppeteering commands per second
  std::vector<GamepadTerm> terms;  // resolved against the head (resolve_gamepad_terms)
  std::string where;

  // A `map:` entry as written, until the head's face layout is known.
  struct PendingTerm {
    GamepadTerm term;  // input resolved; signal, gain and offset still in YAML units
    std::string signal_key;
    std::optional<ConfigNode> signal_node;
  };
  std::vector<PendingTerm> pending;
};

HardwareMode parse_hardware_mode(const ConfigNode& node);
SafetyIoConfig parse_safety_io(const ConfigNode& node);
GamepadConfig parse_gamepad(const ConfigNode& node);

// Resolves the mapping's face signals (named with their YAML unit:
// jaw_pitch_deg, zygomaticus_major_l, eyelid_closure_l) against the head, and
// converts gains and offsets to SI. Throws ConfigError at the entry.
void resolve_gamepad_terms(GamepadConfig& gamepad, const FaceLayout& layout);

}  // namespace facectl
