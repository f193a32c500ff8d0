#include "facectl/face/skin_density.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace facectl::face {

double mean_vertex_area(const TriMesh& m) {
  double area = 0;
  for (const Tri& t : m.tris)
    area += 0.5 * (m.v.get(t[1]) - m.v.get(t[0])).cross(m.v.get(t[2]) - m.v.get(t[0])).norm();
  const std::vector<char> used = used_vertices(m);
  const auto n = std::count(used.begin(), used.end(), 1);
  return n > 0 ? area / static_cast<double>(n) : 0.0;
}

SkinStiffness stiffness_for_vertex_area(const SkinStiffness& k, double ratio) {
  if (!(ratio > 0)) throw std::invalid_argument("stiffness_for_vertex_area: ratio must be > 0");
  const double s = std::min(1.0, ratio);
  SkinStiffness out = k;
  out.stretch = k.stretch * s;
  out.area = k.area * s;
  out.bending = k.bending * (s / ratio);  // exactly k.bending when s = ratio
  out.anchor = k.anchor * ratio * s;
  // On a much coarser skin the anchors can still pass 1: lower all four together.
  const double top = std::max({out.stretch, out.area, out.bending, out.anchor});
  if (top > 1) {
    for (double* v : {&out.stretch, &out.area, &out.bending, &out.anchor}) *v /= top;
  }
  return out;
}

}  // namespace facectl::face
