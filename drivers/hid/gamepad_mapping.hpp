#pragma once

#include <span>
#include <vector>

#include "drivers/hid/gamepad_report.hpp"

namespace facectl {

// Puppeteering: gamepad axes and buttons onto face signals, each term
// `signal = offset + gain · f(input)`, in the signal's SI unit. Axes get a
// dead zone around the centre (rescaled so the output stays continuous);
// buttons give 0 or 1. Signals are resolved to indices by the caller (config).
struct GamepadTerm {
  enum class Source { kAxis, kButton };
  Source source = Source::kAxis;
  std::size_t input = 0;   // axis or button index in the layout
  std::size_t signal = 0;  // face signal index
  double gain = 1.0;
  double offset = 0.0;
  double dead_zone = 0.05;  // axes only, fraction of full scale
};

class GamepadMapping {
 public:
  explicit GamepadMapping(std::vector<GamepadTerm> terms) : terms_(std::move(terms)) {}
  // Sets every mapped signal of `pose` (others untouched). Several terms on one
  // signal add up. No allocation.
  void apply(const GamepadState& state, std::span<double> pose) const;

 private:
  std::vector<GamepadTerm> terms_;
};

}  // namespace facectl
