#include "facectl/face/subdivision.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace facectl::face {
namespace {

// One pass: split up to `budget` longest edges.
Refined split_longest(const Refined& in, std::size_t budget) {
  const TriMesh& m = in.mesh;
  std::vector<Edge> edges = unique_edges(m.tris);
  std::vector<std::pair<double, std::size_t>> len(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i)
    len[i] = {(m.v.get(edges[i].a) - m.v.get(edges[i].b)).squaredNorm(), i};
  std::stable_sort(len.begin(), len.end(), [](auto l, auto r) { return l.first > r.first; });
  budget = std::min(budget, edges.size());

  Refined out = in;
  std::map<std::pair<int, int>, int> mid;
  for (std::size_t k = 0; k < budget; ++k) {
    Edge e = edges[len[k].second];
    int id = static_cast<int>(out.mesh.v.size());
    out.mesh.v.push_back(0.5 * (m.v.get(e.a) + m.v.get(e.b)));
    out.parents.push_back({e.a, e.b});
    mid[{e.a, e.b}] = id;
  }
  auto midpoint = [&](int a, int b) {
    auto it = mid.find({std::min(a, b), std::max(a, b)});
    return it == mid.end() ? -1 : it->second;
  };
  out.mesh.tris.clear();
  for (const Tri& t : m.tris) {
    int m01 = midpoint(t[0], t[1]), m12 = midpoint(t[1], t[2]), m20 = midpoint(t[2], t[0]);
    int n = (m01 >= 0) + (m12 >= 0) + (m20 >= 0);
    auto& T = out.mesh.tris;
    if (n == 0) {
      T.push_back(t);
    } else if (n == 3) {
      T.push_back({t[0], m01, m20});
      T.push_back({m01, t[1], m12});
      T.push_back({m20, m12, t[2]});
      T.push_back({m01, m12, m20});
    } else {
      // Rotate so the first split edge is (r0,r1); winding is preserved.
      int rot = m01 >= 0 ? 0 : (m12 >= 0 ? 1 : 2);
      int r0 = t[rot], r1 = t[(rot + 1) % 3], r2 = t[(rot + 2) % 3];
      int ma = midpoint(r0, r1), mb = midpoint(r1, r2), mc = midpoint(r2, r0);
      if (n == 1) {
        T.push_back({r0, ma, r2});
        T.push_back({ma, r1, r2});
      } else if (mb >= 0) {
        T.push_back({r0, ma, r2});
        T.push_back({ma, r1, mb});
        T.push_back({ma, mb, r2});
      } else {
        T.push_back({r0, ma, mc});
        T.push_back({ma, r1, r2});
        T.push_back({ma, r2, mc});
      }
    }
  }
  return out;
}

}  // namespace

Refined refine_to_vertex_count(const TriMesh& base, std::size_t target) {
  Refined r{base, {}};
  for (std::size_t i = 0; i < base.v.size(); ++i)
    r.parents.push_back({static_cast<int>(i), static_cast<int>(i)});
  while (r.mesh.v.size() < target) r = split_longest(r, target - r.mesh.v.size());
  return r;
}

}  // namespace facectl::face
