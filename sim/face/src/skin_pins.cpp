#include "facectl/face/skin_pins.hpp"

#include <stdexcept>
#include <string>

namespace facectl::face {

void reserve_skin_pins(SkinPins& pins, std::size_t capacity, std::size_t vertices) {
  pins.vertex.assign(capacity, 0);
  pins.vertices = vertices;
  pins.target.resize(capacity);
  pins.count = 0;
}

void clear_skin_pins(SkinPins& pins) {
  pins.count = 0;
}

void add_skin_pin(SkinPins& pins, int vertex, const Vec3& target) {
  const auto j = static_cast<std::size_t>(pins.count);
  if (j >= pins.vertex.size())
    throw std::length_error("add_skin_pin: more pins than reserved (" +
                            std::to_string(pins.vertex.size()) + ")");
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= pins.vertices)
    throw std::out_of_range("add_skin_pin: vertex " + std::to_string(vertex) +
                            " is not on the skin (" + std::to_string(pins.vertices) + " vertices)");
  pins.vertex[j] = vertex;
  pins.target.set(j, target);
  ++pins.count;
}

void apply_skin_pins(const SkinPins& pins, Points& p) {
  for (int j = 0; j < pins.count; ++j) {
    const auto k = static_cast<std::size_t>(j);
    p.set(static_cast<std::size_t>(pins.vertex[k]), pins.target.get(k));
  }
}

}  // namespace facectl::face
