#include "test_heads.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "facectl/face/face_model.hpp"
#include "facectl/face/subdivision.hpp"

namespace facectl::face::testing {

namespace {

// The surface sampled on a regular grid in the front-view (x, y) plane: each grid point
// cast along −z onto the surface, the frontmost hit kept (a height field: the overhang
// under the nose is bridged). Each grid cell becomes two triangles where all three
// corners hit; vertices left in no triangle are dropped.
TriMesh resample_on_grid(const TriMesh& m, double h) {
  Vec3 lo = m.v.get(0), hi = lo;
  for (std::size_t i = 0; i < m.v.size(); ++i) {
    lo = lo.cwiseMin(m.v.get(i));
    hi = hi.cwiseMax(m.v.get(i));
  }
  const int nx = static_cast<int>((hi.x() - lo.x()) / h) + 1;
  const int ny = static_cast<int>((hi.y() - lo.y()) / h) + 1;
  std::vector<int> id(static_cast<std::size_t>(nx * ny), -1);
  TriMesh grid;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = lo.x() + (i + 0.5) * h, y = lo.y() + (j + 0.5) * h;
      double z = -std::numeric_limits<double>::infinity();
      for (const Tri& t : m.tris) {
        const Vec3 a = m.v.get(t[0]), b = m.v.get(t[1]), c = m.v.get(t[2]);
        const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
        if (std::abs(det) < 1e-14) continue;  // seen edge-on
        const double u = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
        const double v = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
        if (u < 0 || v < 0 || u + v > 1) continue;
        z = std::max(z, a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z()));
      }
      if (std::isfinite(z)) {
        id[static_cast<std::size_t>(j * nx + i)] = static_cast<int>(grid.v.size());
        grid.v.push_back(Vec3(x, y, z));
      }
    }
  auto at = [&](int i, int j) { return id[static_cast<std::size_t>(j * nx + i)]; };
  auto keep = [](const Tri& t) { return t[0] >= 0 && t[1] >= 0 && t[2] >= 0; };
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      for (const Tri& t : {Tri{a, b, c}, Tri{a, c, d}})  // counter-clockwise seen from +z
        if (keep(t)) grid.tris.push_back(t);
    }
  std::vector<int> index(grid.v.size(), -1);
  TriMesh out;
  for (Tri t : grid.tris) {
    for (int& k : t) {
      if (index[static_cast<std::size_t>(k)] < 0) {
        index[static_cast<std::size_t>(k)] = static_cast<int>(out.v.size());
        out.v.push_back(grid.v.get(static_cast<std::size_t>(k)));
      }
      k = index[static_cast<std::size_t>(k)];
    }
    out.tris.push_back(t);
  }
  return out;
}

}  // namespace

// std::mt19937 and the swaps are specified, so the order is reproducible; the committed test
// heads depend on it (TestHeads.CommittedMeshesMatchTheGenerator).
Renumbered renumbered(const TriMesh& m, unsigned seed, bool reorder_faces) {
  Renumbered out;
  std::vector<int>& order = out.old_of;
  order.resize(m.v.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 rng(seed);
  for (std::size_t i = order.size() - 1; i > 0; --i)
    std::swap(order[i], order[std::uniform_int_distribution<std::size_t>(0, i)(rng)]);
  std::vector<int> new_index(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    new_index[order[k]] = static_cast<int>(k);
    out.mesh.v.push_back(m.v.get(order[k]));
  }
  for (const Tri& t : m.tris) {
    Tri r{new_index[t[0]], new_index[t[1]], new_index[t[2]]};
    if (reorder_faces) std::rotate(r.begin(), r.begin() + static_cast<long>(rng() % 3), r.end());
    out.mesh.tris.push_back(r);
  }
  if (reorder_faces) std::shuffle(out.mesh.tris.begin(), out.mesh.tris.end(), rng);
  return out;
}

TriMesh make_test_head(const HeadSpec& source, const HeadWarp& w) {
  TriMesh m = read_base_skin(source);
  if (w.grid <= 0) m = refine_to_vertex_count(m, static_cast<std::size_t>(w.vertices)).mesh;
  for (std::size_t i = 0; i < m.v.size(); ++i) m.v.set(i, w.apply(m.v.get(i)));
  if (w.grid > 0) m = resample_on_grid(m, w.grid);
  return renumbered(m, w.shuffle_seed, false).mesh;
}

Vec3 true_landmark(const HeadSpec&, const TriMesh& source_skin, const LandmarkSpec& l,
                   const HeadWarp& w) {
  return w.apply(landmark_position(l, source_skin.v));
}

}  // namespace facectl::face::testing
