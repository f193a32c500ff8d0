#pragma once

#include <cstddef>

namespace facectl {

// Compile-time maxima. Real-time records (commands, telemetry) are fixed-size
// so that they can live in preallocated lock-free buffers; configs larger than
// these are rejected at load time with a clear error.
inline constexpr std::size_t kMaxFaceSignals = 96;
inline constexpr std::size_t kMaxActuators = 64;
inline constexpr std::size_t kMaxBuses = 8;

}  // namespace facectl
