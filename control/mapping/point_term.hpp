#pragma once

#include <array>
#include <cstddef>

namespace facectl {

// A control-point source: gain · (displacement of the point · unit axis),
// displacement from the reduced face model in metres (head frame).
struct PointTerm {
  std::size_t actuator = 0;
  std::size_t point = 0;  // index into the reduced model's control points
  std::array<double, 3> axis{};
  double gain = 0.0;  // effector SI per metre
};

}  // namespace facectl
