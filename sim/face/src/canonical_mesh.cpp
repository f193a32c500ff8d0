#include "facectl/face/canonical_mesh.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace facectl::face {

CanonicalMesh canonical_mesh(const TriMesh& m) {
  CanonicalMesh c;
  const std::size_t n = m.v.size();
  c.original.resize(n);
  std::iota(c.original.begin(), c.original.end(), 0);
  std::stable_sort(c.original.begin(), c.original.end(), [&](int a, int b) {
    const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
    return std::tie(m.v.x[i], m.v.y[i], m.v.z[i]) < std::tie(m.v.x[j], m.v.y[j], m.v.z[j]);
  });
  std::vector<int> canonical(n);
  c.mesh.v.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto o = static_cast<std::size_t>(c.original[k]);
    canonical[o] = static_cast<int>(k);
    c.mesh.v.set(k, m.v.get(o));
  }
  c.mesh.tris.reserve(m.tris.size());
  for (const Tri& t : m.tris) {
    Tri r{canonical[static_cast<std::size_t>(t[0])], canonical[static_cast<std::size_t>(t[1])],
          canonical[static_cast<std::size_t>(t[2])]};
    std::rotate(r.begin(), std::min_element(r.begin(), r.end()), r.end());
    c.mesh.tris.push_back(r);
  }
  std::sort(c.mesh.tris.begin(), c.mesh.tris.end());
  return c;
}

void to_original_indices(const CanonicalMesh& c, std::vector<int>& vertices) {
  for (int& v : vertices) v = c.original[static_cast<std::size_t>(v)];
}

}  // namespace facectl::face
