#include "facectl/face/mesh.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <queue>
#include <utility>

namespace facectl::face {

std::vector<char> used_vertices(const TriMesh& m) {
  std::vector<char> used(m.v.size(), 0);
  for (const Tri& t : m.tris)
    for (int i : t) used[static_cast<std::size_t>(i)] = 1;
  return used;
}

std::vector<Edge> unique_edges(const std::vector<Tri>& tris) {
  std::vector<Edge> e;
  e.reserve(tris.size() * 3);
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      e.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(e.begin(), e.end(), [](Edge l, Edge r) { return l.a != r.a ? l.a < r.a : l.b < r.b; });
  e.erase(std::unique(e.begin(), e.end(), [](Edge l, Edge r) { return l.a == r.a && l.b == r.b; }),
          e.end());
  return e;
}

std::vector<EdgePair> interior_edge_pairs(const std::vector<Tri>& tris) {
  std::map<std::pair<int, int>, std::vector<int>> opp;  // edge -> opposite vertices
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      opp[{std::min(a, b), std::max(a, b)}].push_back(c);
    }
  std::vector<EdgePair> out;
  for (const auto& [e, o] : opp)
    if (o.size() == 2) out.push_back({e.first, e.second, o[0], o[1]});
  return out;
}

std::vector<std::vector<int>> boundary_loops(const std::vector<Tri>& tris) {
  std::map<std::pair<int, int>, int> count;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  // Directed boundary edges keep the triangle's winding, so each loop walks one way.
  std::map<int, int> next;
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      if (count[{std::min(a, b), std::max(a, b)}] == 1) next[a] = b;
    }
  std::vector<std::vector<int>> loops;
  std::map<int, bool> used;
  for (const auto& [s, unused] : next) {
    (void)unused;
    if (used[s]) continue;
    std::vector<int> loop;
    int u = s;
    while (!used[u] && next.count(u)) {
      used[u] = true;
      loop.push_back(u);
      u = next[u];
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

Vec3 triangle_normal(const Points& v, const Tri& t) {
  Vec3 n = (v.get(t[1]) - v.get(t[0])).cross(v.get(t[2]) - v.get(t[0]));
  double l = n.norm();
  return l > 0 ? Vec3(n / l) : Vec3(0, 0, 0);
}

void vertex_normals(const Points& v, const std::vector<Tri>& tris, Points& out) {
  out.resize(v.size());
  std::fill(out.x.begin(), out.x.end(), 0.0);
  std::fill(out.y.begin(), out.y.end(), 0.0);
  std::fill(out.z.begin(), out.z.end(), 0.0);
  for (const Tri& t : tris) {
    Vec3 n = (v.get(t[1]) - v.get(t[0])).cross(v.get(t[2]) - v.get(t[0]));
    for (int k = 0; k < 3; ++k) out.add(t[k], n);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    Vec3 n = out.get(i);
    double l = n.norm();
    out.set(i, l > 0 ? Vec3(n / l) : Vec3(0, 0, 1));
  }
}

Adjacency vertex_adjacency(std::size_t n, const std::vector<Tri>& tris) {
  return adjacency_from_edges(n, unique_edges(tris));
}

Adjacency adjacency_from_edges(std::size_t n, const std::vector<Edge>& e) {
  Adjacency adj;
  adj.start.assign(n + 1, 0);
  for (Edge ed : e) {
    ++adj.start[ed.a + 1];
    ++adj.start[ed.b + 1];
  }
  for (std::size_t i = 0; i < n; ++i) adj.start[i + 1] += adj.start[i];
  adj.nbr.resize(adj.start[n]);
  std::vector<int> fill(adj.start.begin(), adj.start.end() - 1);
  for (Edge ed : e) {
    adj.nbr[fill[ed.a]++] = ed.b;
    adj.nbr[fill[ed.b]++] = ed.a;
  }
  return adj;
}

std::vector<double> edge_geodesic(const Points& v, const Adjacency& adj,
                                  const std::vector<int>& seeds) {
  std::vector<double> d(v.size(), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  for (int s : seeds) {
    d[s] = 0;
    q.push({0.0, s});
  }
  while (!q.empty()) {
    auto [du, u] = q.top();
    q.pop();
    if (du > d[u]) continue;
    for (int k = adj.start[u]; k < adj.start[u + 1]; ++k) {
      int w = adj.nbr[k];
      double nd = du + (v.get(u) - v.get(w)).norm();
      if (nd < d[w]) {
        d[w] = nd;
        q.push({nd, w});
      }
    }
  }
  return d;
}

}  // namespace facectl::face
