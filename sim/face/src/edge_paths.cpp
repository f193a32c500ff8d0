#include "facectl/face/edge_paths.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

namespace facectl::face {

Adjacency path_adjacency(const Points& v, const std::vector<Tri>& tris) {
  std::vector<Edge> edges = unique_edges(tris);
  // Coincident vertices: neighbours once sorted by position.
  std::vector<int> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) {
    const std::size_t k = static_cast<std::size_t>(i);
    return std::make_tuple(v.x[k], v.y[k], v.z[k]);
  };
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return std::make_tuple(key(a), a) < std::make_tuple(key(b), b); });
  for (std::size_t k = 0; k + 1 < order.size(); ++k)
    for (std::size_t j = k + 1; j < order.size() && key(order[j]) == key(order[k]); ++j)
      edges.push_back({std::min(order[k], order[j]), std::max(order[k], order[j])});
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return std::tie(a.a, a.b) < std::tie(b.a, b.b); });
  edges.erase(std::unique(edges.begin(), edges.end(),
                          [](const Edge& a, const Edge& b) { return a.a == b.a && a.b == b.b; }),
              edges.end());
  return adjacency_from_edges(v.size(), edges);
}

std::vector<int> edge_path(const Points& v, const Adjacency& adj, int a, int b) {
  if (a == b) return {};
  // Dijkstra from a on (length, edge count); predecessors form a tree, so the walk back
  // from b ends at a even where zero-length edges tie.
  const std::size_t n = v.size();
  std::vector<double> d(n, std::numeric_limits<double>::infinity());
  std::vector<int> hops(n, std::numeric_limits<int>::max()), pred(n, -1);
  using Item = std::tuple<double, int, int>;  // length, edges, vertex
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  d[a] = 0;
  hops[a] = 0;
  q.push({0.0, 0, a});
  while (!q.empty()) {
    const auto [du, hu, u] = q.top();
    q.pop();
    if (std::tie(du, hu) > std::tie(d[u], hops[u])) continue;
    if (u == b) break;
    for (int k = adj.start[u]; k < adj.start[u + 1]; ++k) {
      const int w = adj.nbr[k];
      const double nd = du + (v.get(u) - v.get(w)).norm();
      const int nh = hu + 1;
      if (std::tie(nd, nh) < std::tie(d[w], hops[w])) {
        d[w] = nd;
        hops[w] = nh;
        pred[w] = u;
        q.push({nd, nh, w});
      } else if (nd == d[w] && nh == hops[w] && u < pred[w]) {
        pred[w] = u;  // same key: the lower index, whatever the order of the queue
      }
    }
  }
  if (pred[b] < 0) return {};
  std::vector<int> path;
  for (int u = pred[b]; u != a; u = pred[u]) path.push_back(u);
  path.push_back(a);
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<int> join_contour(const Points& v, const Adjacency& adj, std::vector<int> snapped) {
  snapped.erase(std::unique(snapped.begin(), snapped.end()), snapped.end());
  while (snapped.size() > 1 && snapped.back() == snapped.front()) snapped.pop_back();
  if (snapped.size() < 3) return {};
  std::vector<int> contour;
  for (std::size_t k = 0; k < snapped.size(); ++k) {
    const std::vector<int> part = edge_path(v, adj, snapped[k], snapped[(k + 1) % snapped.size()]);
    if (part.empty()) return {};
    for (int u : part)
      if (std::find(contour.begin(), contour.end(), u) == contour.end()) contour.push_back(u);
  }
  return contour;
}

}  // namespace facectl::face
