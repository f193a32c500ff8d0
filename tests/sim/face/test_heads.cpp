#include "test_heads.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include "facectl/face/face_model.hpp"
#include "facectl/face/subdivision.hpp"

namespace facectl::face::testing {

TriMesh make_test_head(const HeadSpec& source, const HeadWarp& w) {
  TriMesh m =
      refine_to_vertex_count(read_base_skin(source), static_cast<std::size_t>(w.vertices)).mesh;
  for (std::size_t i = 0; i < m.v.size(); ++i) m.v.set(i, w.apply(m.v.get(i)));
  // Shuffle the vertex order (std::mt19937 is specified, so the order is reproducible).
  std::vector<int> order(m.v.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 rng(w.shuffle_seed);
  for (std::size_t i = order.size() - 1; i > 0; --i)
    std::swap(order[i], order[std::uniform_int_distribution<std::size_t>(0, i)(rng)]);
  std::vector<int> new_index(order.size());
  TriMesh out;
  for (std::size_t k = 0; k < order.size(); ++k) {
    new_index[order[k]] = static_cast<int>(k);
    out.v.push_back(m.v.get(order[k]));
  }
  for (const Tri& t : m.tris)
    out.tris.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  return out;
}

Vec3 true_landmark(const HeadSpec&, const TriMesh& source_skin, const LandmarkSpec& l,
                   const HeadWarp& w) {
  return w.apply(landmark_position(l, source_skin.v));
}

}  // namespace facectl::face::testing
