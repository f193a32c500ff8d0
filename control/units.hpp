// Angles: SI (rad) inside the code, degrees in files and on the wire. The one
// definition of each conversion.
#pragma once

#include <numbers>

namespace facectl {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = std::numbers::pi / 180.0;        // rad per degree
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;  // degrees per rad

}  // namespace facectl
