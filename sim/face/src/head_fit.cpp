#include "facectl/face/head_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <string>

#include "facectl/face/canonical_mesh.hpp"
#include "facectl/face/edge_paths.hpp"
#include "facectl/face/face_model.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/skin_density.hpp"

namespace facectl::face {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box {
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Vec3 size() const { return hi - lo; }
  Vec3 centre() const { return 0.5 * (lo + hi); }
};

Box box_of(const Points& v) {
  Box b;
  for (std::size_t i = 0; i < v.size(); ++i) b.add(v.get(i));
  return b;
}

// The vertices some triangle uses (used) or none does (!used), ascending.
std::vector<int> vertices_by_use(const TriMesh& m, bool used) {
  const std::vector<char> in_face = used_vertices(m);
  std::vector<int> out;
  for (std::size_t i = 0; i < in_face.size(); ++i)
    if ((in_face[i] != 0) == used) out.push_back(static_cast<int>(i));
  return out;
}

// The vertices some triangle uses, ascending (a cut mesh keeps the others).
std::vector<int> surface_vertices(const TriMesh& m) {
  return vertices_by_use(m, true);
}

// The box of the listed vertices only (a cut mesh keeps vertices no face uses).
Box box_of(const Points& v, const std::vector<int>& subset) {
  Box b;
  for (int i : subset) b.add(v.get(i));
  return b;
}

int nearest_of(const Points& v, const std::vector<int>& candidates, const Vec3& p) {
  int best = -1;
  double bd = kInf;
  for (int i : candidates) {
    const double d = (v.get(i) - p).squaredNorm();
    if (d < bd) {
      bd = d;
      best = i;
    }
  }
  return best;
}

// Spread sample of vertices (farthest-point sampling from `seeds`), deterministic.
std::vector<int> spread_samples(const Points& v, std::vector<int> seeds, int count) {
  std::vector<double> d(v.size(), kInf);
  auto update = [&](int s) {
    for (std::size_t i = 0; i < v.size(); ++i)
      d[i] = std::min(d[i], (v.get(i) - v.get(s)).squaredNorm());
  };
  for (int s : seeds) update(s);
  std::vector<int> out;
  for (int k = 0; k < count; ++k) {
    const auto it = std::max_element(d.begin(), d.end());
    if (*it <= 0) break;
    const int s = static_cast<int>(it - d.begin());
    out.push_back(s);
    update(s);
  }
  return out;
}

double median_edge(const TriMesh& m) {
  std::vector<double> len;
  for (const Edge& e : unique_edges(m.tris)) len.push_back((m.v.get(e.a) - m.v.get(e.b)).norm());
  std::nth_element(len.begin(), len.begin() + len.size() / 2, len.end());
  return len[len.size() / 2];
}

std::string mm(double metres) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f mm", metres * 1e3);
  return buf;
}

// A source opening's contour as its ordered boundary loop, once the triangles spanning it
// are cut (the builder's rule); empty when it is not one loop.
std::vector<int> source_loop(const TriMesh& skin, const std::vector<int>& contour) {
  std::vector<char> in(skin.v.size(), 0);
  for (int v : contour) in[v] = 1;
  std::vector<Tri> tris;
  for (const Tri& t : skin.tris)
    if (!(in[t[0]] && in[t[1]] && in[t[2]])) tris.push_back(t);
  for (const auto& loop : boundary_loops(tris))
    if (loop.size() == contour.size() &&
        std::all_of(loop.begin(), loop.end(), [&](int v) { return in[v] != 0; }))
      return loop;
  return {};
}

struct OpeningLoops {
  std::vector<int> source, target;  // ordered boundary loops; target empty: no hole
};

// Cumulative arc length of a closed loop, normalised to [0, 1] (n + 1 entries).
std::vector<double> arc_shares(const Points& v, const std::vector<int>& loop) {
  std::vector<double> s(loop.size() + 1, 0.0);
  for (std::size_t i = 0; i < loop.size(); ++i)
    s[i + 1] = s[i] + (v.get(loop[(i + 1) % loop.size()]) - v.get(loop[i])).norm();
  const double total = s.back();
  for (std::size_t i = 0; i < s.size(); ++i)  // a loop of coincident points: evenly spaced
    s[i] = total > 0 ? s[i] / total : static_cast<double>(i) / static_cast<double>(loop.size());
  return s;
}

Vec3 at_share(const Points& v, const std::vector<int>& loop, const std::vector<double>& s,
              double t) {
  t -= std::floor(t);
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), t) - s.begin() - 1);
  const std::size_t k = std::min(i, loop.size() - 1);
  const double w = (t - s[k]) / std::max(s[k + 1] - s[k], 1e-12);
  return (1 - w) * v.get(loop[k]) + w * v.get(loop[(k + 1) % loop.size()]);
}

// Each source loop vertex's place on the target loop at the same share of arc length, with
// the direction and starting point that best fit `mapped` (the source loop under the
// current morph).
std::vector<Vec3> along_loop(const Points& S, const std::vector<int>& src, const Points& T,
                             std::vector<int> tgt, const std::vector<Vec3>& mapped) {
  const std::vector<double> ss = arc_shares(S, src);
  std::vector<Vec3> best_rim;
  double best = kInf;
  for (int dir = 0; dir < 2; ++dir) {
    if (dir == 1) std::reverse(tgt.begin(), tgt.end());
    const std::vector<double> ts = arc_shares(T, tgt);
    constexpr int kSteps = 256;
    for (int k = 0; k < kSteps; ++k) {
      const double shift = static_cast<double>(k) / kSteps;
      std::vector<Vec3> rim;
      double cost = 0;
      for (std::size_t i = 0; i < src.size(); ++i) {
        rim.push_back(at_share(T, tgt, ts, ss[i] + shift));
        cost += (rim.back() - mapped[i]).squaredNorm();
      }
      if (cost < best) {
        best = cost;
        best_rim = rim;
      }
    }
  }
  return best_rim;
}

// An edge on more than two triangles (a fin, or two sheets joined along a line): the
// boundary loops and edge paths assume a 2-manifold. Names the first such edge in OBJ
// numbering (from 1).
void check_manifold(const TriMesh& m, const std::string& what) {
  std::map<std::pair<int, int>, int> faces;
  for (const Tri& t : m.tris)
    for (int k = 0; k < 3; ++k) ++faces[std::minmax(t[k], t[(k + 1) % 3])];
  int bad = 0;
  std::pair<int, int> first{0, 0};
  int first_count = 0;
  for (const auto& [e, n] : faces)
    if (n > 2 && bad++ == 0) {
      first = e;
      first_count = n;
    }
  if (bad > 0)
    throw InputError(what + ": non-manifold: the edge between vertices " +
                     std::to_string(first.first + 1) + " and " + std::to_string(first.second + 1) +
                     " is shared by " + std::to_string(first_count) + " faces" +
                     (bad > 1 ? " (and " + std::to_string(bad - 1) + " more such edges)" : "") +
                     "; fit-head needs each edge on one or two faces (open borders are fine)");
}

}  // namespace

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = va + vb + vc;
  if (denom <= 0) return a;  // degenerate triangle
  return a + ab * (vb / denom) + ac * (vc / denom);
}

MeshPoint closest_on_mesh(const TriMesh& m, const Vec3& p) {
  MeshPoint best{p, -1};
  double bd = kInf;
  for (std::size_t k = 0; k < m.tris.size(); ++k) {
    const Tri& t = m.tris[k];
    const Vec3 q = closest_point_on_triangle(p, m.v.get(t[0]), m.v.get(t[1]), m.v.get(t[2]));
    const double d = (q - p).squaredNorm();
    if (d < bd) {
      bd = d;
      best = {q, static_cast<int>(k)};
    }
  }
  return best;
}

double mirror_asymmetry(const TriMesh& m, double turn) {
  const std::vector<int> used = surface_vertices(m);
  if (used.empty()) return kInf;
  const Vec3 s = box_of(m.v, used).size();
  int nose = used.front();
  for (int i : used)
    if (m.v.z[i] > m.v.z[nose]) nose = i;
  const Vec3 c = m.v.get(nose);
  const std::size_t step = std::max<std::size_t>(1, used.size() / 200);
  const Vec3 n(std::cos(turn), 0, -std::sin(turn));  // the plane's normal, turned
  std::vector<double> off;
  for (std::size_t k = 0; k < used.size(); k += step) {
    const Vec3 p = m.v.get(used[k]);
    const Vec3 q = p - 2 * (p - c).dot(n) * n;
    off.push_back((closest_on_mesh(m, q).point - q).norm() / s.x());
  }
  std::sort(off.begin(), off.end());
  return off[off.size() * 9 / 10];
}

// The fit aligns the mesh's bounding box with the source face's (forehead to chin, ear to
// ear, the front of the head), without rotating it: a mesh cut otherwise, or turned, fits
// "converged" with the source's chin on the neck or its face on a cheek. Measured on the
// head of Debian's libcgal-demo (tests/data/heads/cgal_head).
void check_face_region(const TriMesh& m, const std::string& what) {
  const Vec3 s = box_of(m.v, surface_vertices(m)).size();
  if (!(s.x() > 0)) throw InputError(what + ": the faces' vertices are flat along x");
  // A face is wider than it is deep (the default head: 155 x 100 mm); a whole head is not.
  if (s.z() >= s.x())
    throw InputError(what + ": " + mm(s.x()) + " wide (x) and " + mm(s.z()) +
                     " deep (z): a whole head, not a face; fit-head aligns bounding boxes, "
                     "so cut the mesh to the face first (forehead to chin, ear to ear, the "
                     "front of the head)");
  // A face looking along +z is mirror-symmetric about the plane x = x(nose tip), the
  // frontmost point. Turned by an angle about y, it is symmetric about that plane turned
  // as much; looking along x, about none (mirror_asymmetry).
  // Turns of up to 12.5 degrees either way, 2.5 apart. Facing +z, at 0: 0 on the default
  // head, 0.022 on the resampled grid_narrow, 0.034 on a 299-vertex bust (libcgal-demo's
  // nefertiti). Facing -x, the CGAL head: 0.120 at best (0.22 at 0). The default head
  // turned by 10 degrees: 0 at 10, 0.165 at 0.
  double best = kInf, turn = 0;
  for (int k = -5; k <= 5; ++k) {
    const double a = mirror_asymmetry(m, k * 2.5 * std::numbers::pi / 180);
    if (a < best) best = a, turn = k * 2.5;
  }
  if (best > 0.07)
    throw InputError(what + ": not mirror-symmetric about any upright plane through its " +
                     "frontmost point (mirrored, a tenth of its points land over " +
                     std::to_string(static_cast<int>(std::lround(100 * best))) +
                     "% of its width from the surface, at best; a face looking along +z "
                     "lands within 4%): expected a face looking along +z with y up; is it "
                     "looking along x?");
  // The fit does not turn the mesh: a turned face is fitted turned.
  if (std::abs(turn) > 5) {
    char degrees[16];
    std::snprintf(degrees, sizeof degrees, "%.1f", std::abs(turn));
    throw InputError(what + ": the face is turned " + degrees + " degrees about y (its nose " +
                     "toward " + (turn > 0 ? "+x" : "-x") +
                     "): turn it to look along +z (up to 5 degrees is accepted)");
  }
}

void check_mesh_basics(const TriMesh& m, const std::string& what) {
  constexpr std::size_t kMinVertices = 100;
  if (m.v.size() < kMinVertices)
    throw InputError(what + ": expected a face mesh of at least " + std::to_string(kMinVertices) +
                     " vertices, found " + std::to_string(m.v.size()));
  std::size_t good = 0;
  for (const Tri& t : m.tris) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw InputError(what + ": a face uses vertex " + std::to_string(t[0] + 1) +
                       " twice (degenerate)");
    const Vec3 n = (m.v.get(t[1]) - m.v.get(t[0])).cross(m.v.get(t[2]) - m.v.get(t[0]));
    if (n.norm() > 0) ++good;
  }
  const std::vector<int> used = surface_vertices(m);
  if (used.size() < kMinVertices)
    throw InputError(what + ": expected faces over at least " + std::to_string(kMinVertices) +
                     " vertices, found " + std::to_string(used.size()));
  check_manifold(m, what);
  if (good * 2 < m.tris.size())
    throw InputError(what + ": most triangles have zero area (degenerate mesh)");
  const Vec3 s = box_of(m.v).size();
  const double big = s.maxCoeff();
  if (!(big > 0)) throw InputError(what + ": all vertices coincide");
  const char* axis = "xyz";
  for (int k = 0; k < 3; ++k)
    if (s[k] < 0.05 * big)
      throw InputError(what + ": flat along " + std::string(1, axis[k]) + " (extent " + mm(s[k]) +
                       " of " + mm(big) + "): expected a face facing +z with y up");
}

void check_head_mesh(const TriMesh& m, const std::string& what) {
  check_mesh_basics(m, what);
  check_face_region(m, what);
}

namespace {

// Step 1, initial alignment: per-axis scale and centre from the bounding boxes (both
// meshes face +z).
struct BoxAlignment {
  Box source, target;
  Vec3 scale;
  Vec3 apply(const Vec3& p) const {
    return target.centre() + scale.cwiseProduct(p - source.centre());
  }
};

BoxAlignment align_boxes(const Points& S, const Points& T, const std::vector<int>& surface) {
  // Vertices no face uses are not the face's (a cut leaves them behind).
  BoxAlignment a{box_of(S), box_of(T, surface), Vec3::Ones()};
  a.scale = a.target.size().cwiseQuotient(a.source.size());
  return a;
}

// Step 2, openings the target already has as holes: the boundary loop near each source
// contour (after the initial alignment), ordered like the source's own loop.
std::vector<OpeningLoops> find_holes(const HeadSpec& source, const TriMesh& source_skin,
                                     const TriMesh& target, const BoxAlignment& al) {
  const Points& T = target.v;
  const auto loops = boundary_loops(target.tris);
  std::vector<OpeningLoops> holes(source.openings.size());
  for (std::size_t oi = 0; oi < source.openings.size(); ++oi) {
    const auto& verts = source.openings[oi].second;
    holes[oi].source = source_loop(source_skin, verts);
    std::vector<Vec3> mapped;
    Box mb;
    for (int v : verts) {
      mapped.push_back(closest_on_mesh(target, al.apply(source_skin.v.get(v))).point);
      mb.add(mapped.back());
    }
    const double span = mb.size().norm();
    double best = kInf;
    for (const auto& loop : loops) {
      Box lb;
      for (int v : loop) lb.add(T.get(v));
      if (lb.size().norm() > 2 * span) continue;  // the face's outer edge, not this opening
      double sum = 0;
      for (const Vec3& p : mapped) sum += (T.get(nearest_of(T, loop, p)) - p).norm();
      const double mean = sum / static_cast<double>(mapped.size());
      if (mean < best) {
        best = mean;
        holes[oi].target = loop;
      }
    }
    if (best >= 0.25 * span || holes[oi].source.empty()) holes[oi].target.clear();
  }
  return holes;
}

// Source points near the rim of an opening the target has as a hole: the rim carries
// them, where a closest point would slide across the curved lips (measured: outer lip
// corners 4.6 mm off).
struct RimProximity {
  const Points& S;
  std::vector<int> rim;
  double reach;
  bool operator()(int v) const {
    for (int r : rim)
      if (r != v && (S.get(r) - S.get(v)).norm() < reach) return true;
    return false;
  }
};

RimProximity rim_proximity(const Points& S, const std::vector<OpeningLoops>& holes, double reach) {
  RimProximity near{S, {}, reach};
  for (const OpeningLoops& h : holes)
    if (!h.target.empty()) near.rim.insert(near.rim.end(), h.source.begin(), h.source.end());
  return near;
}

// Source vertex → index of the opening whose contour it is on, or −1.
std::vector<int> contour_index(const HeadSpec& source, std::size_t n) {
  std::vector<int> on_contour(n, -1);
  for (std::size_t oi = 0; oi < source.openings.size(); ++oi)
    for (int v : source.openings[oi].second) on_contour[v] = static_cast<int>(oi);
  return on_contour;
}

// Source vertices G is fitted at (`vertex`), their source positions (`from`).
struct Correspondences {
  std::vector<int> vertex;
  std::vector<Vec3> from;
  std::map<int, std::size_t> index;  // vertex → position in the lists
  void add(const Points& S, int v) {
    index[v] = vertex.size();
    vertex.push_back(v);
    from.push_back(S.get(v));
  }
};

// Step 3a: every skin landmark vertex and every contour vertex of an opening the target
// has as a hole, plus a spread sample of the skin.
Correspondences choose_correspondences(const HeadSpec& source, const Points& S,
                                       const std::vector<OpeningLoops>& holes,
                                       const std::vector<int>& on_contour,
                                       const RimProximity& near_rim, int samples) {
  std::vector<int> corr;
  for (const LandmarkSpec& l : source.landmarks)
    for (int v : l.vertices)
      if (!near_rim(v) || on_contour[v] >= 0) corr.push_back(v);
  for (const OpeningLoops& h : holes)
    if (!h.target.empty()) corr.insert(corr.end(), h.source.begin(), h.source.end());
  std::sort(corr.begin(), corr.end());
  corr.erase(std::unique(corr.begin(), corr.end()), corr.end());
  for (int v : spread_samples(S, corr, samples))
    if (!near_rim(v)) corr.push_back(v);
  Correspondences c;
  for (int v : corr) c.add(S, v);
  return c;
}

// Step 3b, non-rigid fit. Surface points go to the closest target point; contour points
// of a hole to the same share of arc length along the target's loop (closest points would
// let them slide along the rim, and G interpolates them, so nothing would correct it).
// G changes the closest points, and the rim alignment; repeat until they stop moving.
// Writes fit.morph, iterations, refined_pairs, last_change_mm and converged.
void fit_morph(const Points& S, const TriMesh& target, const std::vector<OpeningLoops>& holes,
               const BoxAlignment& al, const RimProximity& near_rim, Correspondences c,
               const HeadFitOptions& o, HeadFit& fit) {
  auto morph = [&](const Vec3& p) {
    return fit.iterations == 0 ? al.apply(p) : fit.morph.apply(p);
  };
  std::vector<Vec3> to(c.vertex.size()), prev(c.vertex.size(), Vec3::Zero());
  fit.converged = false;
  for (int it = 0; it < o.max_iterations; ++it) {
    for (std::size_t k = 0; k < c.vertex.size(); ++k)
      to[k] = closest_on_mesh(target, morph(c.from[k])).point;
    for (const OpeningLoops& h : holes) {
      if (h.target.empty()) continue;
      std::vector<Vec3> mapped;
      for (int v : h.source) mapped.push_back(morph(S.get(v)));
      const std::vector<Vec3> on_rim = along_loop(S, h.source, target.v, h.target, mapped);
      for (std::size_t i = 0; i < h.source.size(); ++i) to[c.index.at(h.source[i])] = on_rim[i];
    }
    double change = 0;
    for (std::size_t k = 0; k < prev.size(); ++k)
      change = std::max(change, (to[k] - prev[k]).norm());
    fit.morph = fit_rbf(c.from, to);
    prev = to;
    fit.iterations = it + 1;
    fit.last_change_mm = change * 1e3;
    // Refinement (thesis ch. 6): the source vertices the morph leaves farthest from the
    // target surface become correspondences too.
    std::vector<std::pair<double, int>> gap;
    for (int v = 0; v < static_cast<int>(S.size()); ++v) {
      if (c.index.count(v) || near_rim(v)) continue;
      const Vec3 p = fit.morph.apply(S.get(v));
      const double d = (closest_on_mesh(target, p).point - p).norm();
      if (d * 1e3 > o.refine_above_mm) gap.push_back({d, v});
    }
    std::sort(gap.rbegin(), gap.rend());
    gap.resize(std::min<std::size_t>(gap.size(), static_cast<std::size_t>(o.worst_pairs)));
    for (const auto& g : gap) {
      c.add(S, g.second);
      to.push_back(Vec3::Zero());
    }
    fit.refined_pairs += static_cast<int>(gap.size());
    fit.last_added_pairs = static_cast<int>(gap.size());
    if (it > 0 && gap.empty() && fit.last_change_mm < o.converged_mm) {
      fit.converged = true;
      break;
    }
  }
}

// Step 5: the hole found in step 2, else the mapped contour snapped to target vertices and
// joined by shortest edge paths. Notes and problems go to `fit`.
std::vector<std::pair<std::string, std::vector<int>>> place_openings(
    const HeadSpec& source, const Points& S, const TriMesh& target, const std::vector<int>& surface,
    const std::vector<OpeningLoops>& holes, HeadFit& fit) {
  const Adjacency adj = path_adjacency(target.v, target.tris);
  std::vector<std::pair<std::string, std::vector<int>>> openings;
  for (std::size_t oi = 0; oi < source.openings.size(); ++oi) {
    const auto& [name, verts] = source.openings[oi];
    std::vector<int> contour = holes[oi].target;
    if (!contour.empty()) {
      fit.opening_notes.push_back(name + ": the mesh's own hole (" +
                                  std::to_string(contour.size()) + " vertices)");
    } else {
      std::vector<int> snapped;
      for (int v : verts) {
        const Vec3 p = closest_on_mesh(target, fit.morph.apply(S.get(v))).point;
        snapped.push_back(nearest_of(target.v, surface, p));
      }
      contour = join_contour(target.v, adj, snapped);
      if (contour.empty())
        fit.problems.push_back("opening " + name + ": could not close a contour on the mesh");
      else
        fit.opening_notes.push_back(name + ": contour of " + std::to_string(contour.size()) +
                                    " vertices joined along edges (mesh closed there)");
    }
    openings.push_back({name, contour});
  }
  return openings;
}

// Each landmark's point on the source head and where the fit placed it (vertices + offset).
struct LandmarkPositions {
  std::map<std::string, Vec3> source, placed;
};

// Step 4: each source vertex mapped by G and snapped (contour vertices to the matching
// target contour); bone points keep G's position through a new offset. Writes
// fit.landmarks, fit.spec.landmarks and problems.
LandmarkPositions place_landmarks(const HeadSpec& source, const Points& S, const TriMesh& target,
                                  const std::vector<int>& surface,
                                  const std::vector<int>& on_contour, const BoxAlignment& al,
                                  const HeadFitOptions& o, HeadFit& fit) {
  const Points& T = target.v;
  const RbfMorph& G = fit.morph;
  const double edge = median_edge(target);
  LandmarkPositions pos;
  for (std::size_t li = 0; li < source.landmarks.size(); ++li) {
    const LandmarkSpec& l = source.landmarks[li];
    LandmarkSpec& nl = fit.spec.landmarks[li];
    PlacedLandmark p;
    p.name = l.name;
    p.bone = l.offset.norm() > 0;
    const Vec3 src = landmark_position(l, S);
    pos.source[l.name] = src;
    p.fitted = G.apply(src);
    p.initial_mm = (closest_on_mesh(target, al.apply(src)).point - al.apply(src)).norm() * 1e3;
    nl.vertices.clear();
    Vec3 mean = Vec3::Zero();
    for (int v : l.vertices) {
      const int oi = on_contour[v];
      const std::vector<int>& contour = oi >= 0 ? fit.spec.openings[oi].second : surface;
      const int t = nearest_of(T, contour.empty() ? surface : contour, G.apply(S.get(v)));
      nl.vertices.push_back(t);
      mean += T.get(t);
    }
    mean /= static_cast<double>(nl.vertices.size());
    p.vertices = nl.vertices;
    p.offset = p.bone ? Vec3(p.fitted - mean) : Vec3::Zero();
    nl.offset = p.offset;
    p.snap_mm = (mean + p.offset - p.fitted).norm() * 1e3;
    pos.placed[l.name] = mean + p.offset;
    if (!p.bone && p.snap_mm > o.max_snap_edges * edge * 1e3 && l.vertices.size() == 1)
      fit.problems.push_back("landmark " + l.name + ": nearest vertex " + mm(p.snap_mm * 1e-3) +
                             " away (more than " + std::to_string(o.max_snap_edges) +
                             " median edges of " + mm(edge) + ")");
    fit.landmarks.push_back(p);
  }
  return pos;
}

// A face, the right way round: catches meshes with nothing face-like, or facing −z.
void check_orientation(const LandmarkPositions& pos, std::vector<std::string>& problems) {
  const auto& at = pos.placed;
  if (!at.count("fdp_3_7") || !at.count("fdp_3_8") || !at.count("fdp_9_3") || !at.count("fdp_2_2"))
    return;
  const Vec3 eyes = 0.5 * (at.at("fdp_3_7") + at.at("fdp_3_8"));
  if (!(at.at("fdp_3_7").x() > at.at("fdp_3_8").x()))
    problems.push_back("the fitted left eye (fdp_3_7) is not at +x of the right (fdp_3_8)");
  if (!(eyes.y() > at.at("fdp_2_2").y()))
    problems.push_back("the fitted eyes are not above the mouth (y up?)");
  if (!(at.at("fdp_9_3").z() > eyes.z()))
    problems.push_back("the fitted nose tip (fdp_9_3) is not in front of the eyes (+z?)");
}

// Step 6: every muscle corner (source landmark + offset) carried by G, as new landmark +
// offset.
void carry_muscles(const LandmarkPositions& pos, const RbfMorph& G, HeadSpec& h) {
  for (MuscleSpec& m : h.muscles)
    for (auto* refs : {&m.origin, &m.insertion, &m.inner, &m.outer})
      for (PointRef& r : *refs)
        r.offset = G.apply(pos.source.at(r.landmark) + r.offset) - pos.placed.at(r.landmark);
}

// Step 7: lengths that scale with the head; variants are for the user to choose.
void scale_sizes(const LandmarkPositions& pos, double s, HeadSpec& h) {
  h.tissue_depth *= s;
  // The teeth and eyeballs follow the mouth's and the eyes' own widths: a jaw narrower
  // than the bounding box would otherwise push the lip corners onto too wide an arch.
  auto width_ratio = [&](const char* a, const char* b) {
    if (!pos.source.count(a) || !pos.source.count(b)) return s;
    return (pos.placed.at(a) - pos.placed.at(b)).norm() /
           (pos.source.at(a) - pos.source.at(b)).norm();
  };
  h.teeth_half_width *= width_ratio("fdp_8_3", "fdp_8_4");
  h.teeth_depth *= s;
  h.teeth_height *= s;
  h.teeth_inset *= s;
  h.eyelid_band *= s;
  h.eyeball_radius *=
      0.5 * (width_ratio("fdp_3_7", "fdp_3_11") + width_ratio("fdp_3_8", "fdp_3_12"));
  h.influence_falloff *= s;
  for (MuscleSpec& m : h.muscles) m.thickness *= s;
  h.variants.clear();
}

// The fit on a target numbered as given; fit_head runs it on the canonical numbering.
HeadFit fit_numbered(const HeadSpec& source, const TriMesh& source_skin, const TriMesh& target,
                     const HeadFitOptions& o) {
  HeadFit fit;
  const Points& S = source_skin.v;
  // Vertices used by no face are left out: landmarks and contours snap to the surface.
  fit.loose_vertices = loose_vertices(target);
  const std::vector<int> surface = surface_vertices(target);

  const BoxAlignment al = align_boxes(S, target.v, surface);
  fit.size_ratio = std::sqrt(al.scale.x() * al.scale.y());
  const std::vector<OpeningLoops> holes = find_holes(source, source_skin, target, al);
  const std::vector<int> on_contour = contour_index(source, S.size());
  const RimProximity near_rim = rim_proximity(S, holes, o.rim_reach);
  fit_morph(S, target, holes, al, near_rim,
            choose_correspondences(source, S, holes, on_contour, near_rim, o.surface_samples), o,
            fit);

  fit.spec = source;
  fit.spec.openings = place_openings(source, S, target, surface, holes, fit);
  const LandmarkPositions pos = place_landmarks(source, S, target, surface, on_contour, al, o, fit);
  check_orientation(pos, fit.problems);
  carry_muscles(pos, fit.morph, fit.spec);
  scale_sizes(pos, fit.size_ratio, fit.spec);
  // Step 8: the skin's stiffnesses, tuned on the source's vertex density, for the target's,
  // both measured against their face's size (the model has no length scale of its own).
  const double r =
      mean_vertex_area(target) / (mean_vertex_area(source_skin) * fit.size_ratio * fit.size_ratio);
  if (std::isfinite(r) && r > 0) {
    fit.vertex_area_ratio = r;
    fit.spec.skin = stiffness_for_vertex_area(source.skin, r);
  } else {
    fit.problems.push_back(
        "the skin's area per vertex cannot be set against the --from skin's "
        "(ratio " +
        std::to_string(r) + "): its stiffnesses are copied unscaled");
  }
  return fit;
}

}  // namespace

std::vector<int> loose_vertices(const TriMesh& m) {
  return vertices_by_use(m, false);
}

// Discrete choices in the fit (which pairs the refinement adds, when it stops) follow tiny
// differences of rounding, and the order of the target's vertices changed those: the same
// mesh in four vertex orders gave muscle corners up to 0.31 mm apart. On the canonical
// numbering the fit is a function of the surface; its indices are mapped back.
HeadFit fit_head(const HeadSpec& source, const TriMesh& source_skin, const TriMesh& target,
                 const HeadFitOptions& o) {
  const CanonicalMesh c = canonical_mesh(target);
  HeadFit fit = fit_numbered(source, source_skin, c.mesh, o);
  to_original_indices(c, fit.loose_vertices);
  std::sort(fit.loose_vertices.begin(), fit.loose_vertices.end());
  for (PlacedLandmark& l : fit.landmarks) to_original_indices(c, l.vertices);
  for (LandmarkSpec& l : fit.spec.landmarks) to_original_indices(c, l.vertices);
  for (auto& opening : fit.spec.openings) to_original_indices(c, opening.second);
  return fit;
}

}  // namespace facectl::face
