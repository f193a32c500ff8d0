// Building and ordering the constraint sets, and their values.
#include "facectl/face/constraints.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>

#include "batched_access.hpp"
#include "dihedral.hpp"

namespace facectl::face {
namespace {

using batched::kBatch;

// Morton (Z-order) key of a point in the box [lo, lo + span], 10 bits an axis.
std::uint32_t morton(const Vec3& q, const Vec3& lo, const Vec3& span) {
  std::uint32_t key = 0;
  std::uint32_t c[3];
  for (int a = 0; a < 3; ++a) {
    const double t = span[a] > 0 ? (q[a] - lo[a]) / span[a] : 0.0;
    c[a] = static_cast<std::uint32_t>(std::clamp(t, 0.0, 1.0) * 1023.0);
  }
  for (int bit = 9; bit >= 0; --bit)
    for (int a = 0; a < 3; ++a) key = (key << 1) | ((c[a] >> bit) & 1u);
  return key;
}

// Gauss–Seidel order in batches: constraints sorted along a Z-order curve through their
// rest centroids (neighbours in the order are neighbours on the surface, so a batch's
// particles are mostly in cache), then cut greedily into batches of up to kBatch that
// share no particle, each batch taking the first fitting constraints of the next
// kWindow still waiting. `perm[new] = old`; `runs` holds the batch ends. Deterministic:
// it depends only on the index lists and the rest positions.
std::vector<std::size_t> batch_order(const std::vector<const std::vector<int>*>& idx,
                                     const Points& rest, std::vector<int>& runs) {
  constexpr std::size_t kWindow = 64;
  const std::size_t n = idx[0]->size();
  std::vector<Vec3> centre(n, Vec3::Zero());
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto* v : idx) centre[i] += rest.get((*v)[i]);
    centre[i] /= static_cast<double>(idx.size());
    // The key uses |x|, the distance from the head's sagittal plane x = 0, so a constraint
    // and its mirror image sit side by side in the order (a left-first tie-break keeps it
    // deterministic): left and right are solved alike and the face stays symmetric.
    centre[i].x() = std::abs(centre[i].x());
    lo = lo.cwiseMin(centre[i]);
    hi = hi.cwiseMax(centre[i]);
  }
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    double side = 0;  // mean signed x, for the tie-break
    for (const auto* v : idx) side += rest.x[(*v)[i]];
    key[i] = (std::uint64_t{morton(centre[i], lo, hi - lo)} << 1) | (side < 0 ? 1u : 0u);
  }
  std::vector<std::size_t> waiting(n);
  for (std::size_t i = 0; i < n; ++i) waiting[i] = i;
  std::stable_sort(waiting.begin(), waiting.end(),
                   [&](std::size_t x, std::size_t y) { return key[x] < key[y]; });
  std::vector<std::size_t> perm;
  std::vector<int> busy(rest.size(), -1);  // batch that holds a particle
  runs.clear();
  std::size_t head = 0;  // waiting[head..] are not placed yet; placed ones are marked
  std::vector<char> placed(n, 0);
  while (perm.size() < n) {
    const int batch = static_cast<int>(runs.size());
    std::size_t taken = 0, seen = 0;
    for (std::size_t w = head; w < n && seen < kWindow && taken < kBatch; ++w) {
      const std::size_t c = waiting[w];
      if (placed[c]) continue;
      ++seen;
      bool free = true;
      for (const auto* v : idx) free = free && busy[(*v)[c]] != batch;
      if (!free) continue;
      for (const auto* v : idx) busy[(*v)[c]] = batch;
      placed[c] = 1;
      perm.push_back(c);
      ++taken;
    }
    while (head < n && placed[waiting[head]]) ++head;
    runs.push_back(static_cast<int>(perm.size()));
  }
  return perm;
}

template <class T>
void permute(std::vector<T>& v, const std::vector<std::size_t>& perm) {
  std::vector<T> out(v.size());
  for (std::size_t i = 0; i < perm.size(); ++i) out[i] = v[perm[i]];
  v.swap(out);
}

}  // namespace

void DistanceConstraints::add(int ia, int ib, double r, double stiffness) {
  runs.clear();  // the runs no longer cover the set
  a.push_back(ia);
  b.push_back(ib);
  rest.push_back(r);
  k.push_back(stiffness);
}
void BendingConstraints::add(int ia, int ib, int ic, int id, double r, double stiffness) {
  runs.clear();
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  d.push_back(id);
  rest.push_back(r);
  cos_rest.push_back(std::cos(r));
  sin_rest.push_back(std::sin(r));
  k.push_back(stiffness);
}
void BendingConstraints::add_at_rest(const Points& p, int ia, int ib, int ic, int id,
                                     double stiffness) {
  const Dihedral h = dihedral(p, ia, ib, ic, id);
  add(ia, ib, ic, id, h.valid ? std::atan2(h.sin, h.cos) : 0.0, stiffness);
  if (h.valid) {  // the measured pair itself, so C is exactly 0 at rest
    cos_rest.back() = h.cos;
    sin_rest.back() = h.sin;
  }
}
void AreaConstraints::add(int ia, int ib, int ic, double r, double stiffness) {
  runs.clear();
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  rest.push_back(r);
  k.push_back(stiffness);
}
void OrientationConstraints::add(int ia, int ib, int ic, const Vec3& unit_normal, double min_value,
                                 double stiffness) {
  runs.clear();
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  nx.push_back(unit_normal.x());
  ny.push_back(unit_normal.y());
  nz.push_back(unit_normal.z());
  min.push_back(min_value);
  k.push_back(stiffness);
}
void Attachments::add(int i, double stiffness) {
  particle.push_back(i);
  k.push_back(stiffness);
}

double distance_value(const DistanceConstraints& s, std::size_t i, const Points& p) {
  return (p.get(s.a[i]) - p.get(s.b[i])).norm() - s.rest[i];
}

double bending_angle(const Points& p, int a, int b, int c, int d) {
  const Dihedral h = dihedral(p, a, b, c, d);
  return h.valid ? std::atan2(h.sin, h.cos) : 0.0;
}

double area_value(const AreaConstraints& s, std::size_t i, const Points& p) {
  Vec3 p1 = p.get(s.a[i]);
  return 0.5 * (p.get(s.b[i]) - p1).cross(p.get(s.c[i]) - p1).norm() - s.rest[i];
}

double volume_of(const VolumeConstraint& v, const Points& p) {
  double sum = 0;
  for (const Tri& t : v.tris)
    sum += (p.get(t[0]) - v.origin).cross(p.get(t[1]) - v.origin).dot(p.get(t[2]) - v.origin);
  return sum;
}

namespace {
template <class T>
void append_to(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}
}  // namespace

void append(DistanceConstraints& to, const DistanceConstraints& from) {
  to.runs.clear();
  for (auto [t, f] : {std::pair{&to.a, &from.a}, {&to.b, &from.b}}) append_to(*t, *f);
  for (auto [t, f] : {std::pair{&to.rest, &from.rest}, {&to.k, &from.k}}) append_to(*t, *f);
}

void append(BendingConstraints& to, const BendingConstraints& from) {
  to.runs.clear();
  for (auto [t, f] :
       {std::pair{&to.a, &from.a}, {&to.b, &from.b}, {&to.c, &from.c}, {&to.d, &from.d}})
    append_to(*t, *f);
  for (auto [t, f] : {std::pair{&to.rest, &from.rest},
                      {&to.cos_rest, &from.cos_rest},
                      {&to.sin_rest, &from.sin_rest},
                      {&to.k, &from.k}})
    append_to(*t, *f);
}

void order_in_runs(DistanceConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b}, rest, s.runs);
  for (auto* v : {&s.a, &s.b}) permute(*v, perm);
  for (auto* v : {&s.rest, &s.k}) permute(*v, perm);
}

void order_in_runs(BendingConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b, &s.c, &s.d}, rest, s.runs);
  for (auto* v : {&s.a, &s.b, &s.c, &s.d}) permute(*v, perm);
  for (auto* v : {&s.rest, &s.cos_rest, &s.sin_rest, &s.k}) permute(*v, perm);
}

void order_in_runs(AreaConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b, &s.c}, rest, s.runs);
  for (auto* v : {&s.a, &s.b, &s.c}) permute(*v, perm);
  for (auto* v : {&s.rest, &s.k}) permute(*v, perm);
}

void order_in_runs(OrientationConstraints& s, const Points& rest) {
  const auto perm = batch_order({&s.a, &s.b, &s.c}, rest, s.runs);
  for (auto* v : {&s.a, &s.b, &s.c}) permute(*v, perm);
  for (auto* v : {&s.nx, &s.ny, &s.nz, &s.min, &s.k}) permute(*v, perm);
}

void add_edge_distances(DistanceConstraints& s, const Points& p, const std::vector<Tri>& tris,
                        double k) {
  for (Edge e : unique_edges(tris)) s.add(e.a, e.b, (p.get(e.a) - p.get(e.b)).norm(), k);
  order_in_runs(s, p);
}

void add_bending(BendingConstraints& s, const Points& p, const std::vector<Tri>& tris, double k) {
  for (EdgePair e : interior_edge_pairs(tris)) s.add_at_rest(p, e.a, e.b, e.c, e.d, k);
  order_in_runs(s, p);
}

void add_areas(AreaConstraints& s, const Points& p, const std::vector<Tri>& tris, double k) {
  for (const Tri& t : tris) {
    s.add(t[0], t[1], t[2], 0, k);
    s.rest.back() = area_value(s, s.size() - 1, p);
  }
  order_in_runs(s, p);
}

void add_orientations(OrientationConstraints& s, const Points& p, const std::vector<Tri>& tris,
                      double min_fraction, double k) {
  for (const Tri& t : tris) {
    const Vec3 cr = (p.get(t[1]) - p.get(t[0])).cross(p.get(t[2]) - p.get(t[0]));
    const double len = cr.norm();
    if (len > 0) s.add(t[0], t[1], t[2], cr / len, min_fraction * len, k);
  }
  order_in_runs(s, p);
}

PairStretch split_pair_stretch(DistanceConstraints& edges, const BendingConstraints& bending,
                               const Points& rest) {
  std::map<std::pair<int, int>, std::size_t> edge_of;
  for (std::size_t i = 0; i < edges.size(); ++i)
    edge_of.emplace(std::minmax(edges.a[i], edges.b[i]), i);
  std::vector<char> paired(edges.size(), 0);
  PairStretch out;
  for (std::size_t i = 0; i < bending.size(); ++i) {
    const auto e = edge_of.find(std::minmax(bending.a[i], bending.b[i]));
    const bool first = e != edge_of.end() && !paired[e->second];
    out.rest.push_back(first ? edges.rest[e->second] : 0.0);
    out.k.push_back(first ? edges.k[e->second] : 0.0);
    if (first) paired[e->second] = 1;
  }
  DistanceConstraints border;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (!paired[i]) border.add(edges.a[i], edges.b[i], edges.rest[i], edges.k[i]);
  order_in_runs(border, rest);
  edges = std::move(border);
  return out;
}

VolumeConstraint make_volume(const Points& p, const std::vector<Tri>& tris, const Vec3& origin,
                             double k) {
  VolumeConstraint v;
  v.tris = tris;
  for (const Tri& t : tris) v.verts.insert(v.verts.end(), t.begin(), t.end());
  std::sort(v.verts.begin(), v.verts.end());
  v.verts.erase(std::unique(v.verts.begin(), v.verts.end()), v.verts.end());
  v.origin = origin;
  v.k = k;
  v.rest = volume_of(v, p);
  return v;
}

}  // namespace facectl::face
