#include "facectl/face/skin_density.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
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
  if (!(ratio > 0 && std::isfinite(ratio)))
    throw std::invalid_argument(
        "stiffness_for_vertex_area: the ratio must be finite and > 0, not " +
        std::to_string(ratio));
  // The weights relative to stretch and area, then all four scaled so that the largest is
  // the source's largest: PBD needs every k <= 1, and a fit there and back gives k again.
  SkinStiffness out = k;
  out.bending = k.bending / ratio;
  out.anchor = k.anchor * ratio;
  const double was = std::max({k.stretch, k.area, k.bending, k.anchor});
  const double now = std::max({out.stretch, out.area, out.bending, out.anchor});
  if (now > 0)
    for (double* v : {&out.stretch, &out.area, &out.bending, &out.anchor}) *v *= was / now;
  return out;
}

}  // namespace facectl::face
