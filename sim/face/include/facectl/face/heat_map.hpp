// Displacement heat maps: per-vertex |displacement| of the skin from a reference pose in
// mm, the colour ramp that shows it, and the colour bar that states the scale.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "facectl/face/image.hpp"
#include "facectl/face/points.hpp"

namespace facectl::face {

using Rgb8 = std::array<std::uint8_t, 3>;

// |a[i] − b[i]| in mm for every vertex; throws std::invalid_argument on a size mismatch.
std::vector<double> displacement_mm(const Points& a, const Points& b);
// The ramp at t ∈ [0, 1] (clamped): dark blue at 0 through cyan, green and yellow to red
// at 1, so that equal steps in mm read as distinct hues.
Rgb8 heat_colour(double t);
// A strip `width` pixels wide: the ramp from 0 to `max_mm` with tick values every
// `step` mm and the caption "|displacement from neutral|, mm". Throws
// std::invalid_argument unless max_mm > 0 and width ≥ 120.
Image colour_bar(int width, double max_mm);

}  // namespace facectl::face
