#pragma once

#include <array>
#include <cstdint>

#include "control/capacity.hpp"

namespace facectl {

// One face command as an input source sends it: every signal of the head's
// FaceLayout, in SI units. Plain data so that it can cross the lock-free
// mailbox by copy.
struct FaceCommand {
  std::array<double, kMaxFaceSignals> values{};
  std::uint64_t sequence = 0;  // incremented by the producer for every command
  std::int64_t stamp_ns = 0;   // CLOCK_MONOTONIC time the producer made it
};

}  // namespace facectl
