// Skin pins: chosen skin vertices held at given positions, as the points of an
// animatronic skin are held by their actuators. Solved last in each skin iteration and
// again at the end of the frame (step_face), so a pinned vertex ends the frame on its
// target. Storage is reserved once; setting pins and stepping never allocate.
#pragma once

#include <cstddef>
#include <vector>

#include "facectl/face/points.hpp"

namespace facectl::face {

struct SkinPins {
  std::vector<int> vertex;  // capacity() pins are reserved; the first `count` are active
  Points target;            // metres, model frame
  int count = 0;
  std::size_t vertices = 0;  // the skin's vertex count: a pin's vertex is below it
};

// Reserves room for `capacity` pins on a skin of `vertices` vertices and clears them.
void reserve_skin_pins(SkinPins& pins, std::size_t capacity, std::size_t vertices);
void clear_skin_pins(SkinPins& pins);
// Adds a pin; throws std::length_error beyond the reserved capacity and
// std::out_of_range for a vertex not on the skin (never allocates).
void add_skin_pin(SkinPins& pins, int vertex, const Vec3& target);
// Moves every active pin's vertex onto its target.
void apply_skin_pins(const SkinPins& pins, Points& p);

}  // namespace facectl::face
