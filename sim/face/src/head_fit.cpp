#include "facectl/face/head_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "facectl/face/input_error.hpp"

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

// Closest point on the target surface (all triangles; meshes here have a few thousand).
Vec3 closest_on_mesh(const TriMesh& m, const Vec3& p) {
  Vec3 best = p;
  double bd = kInf;
  for (const Tri& t : m.tris) {
    const Vec3 q = closest_point_on_triangle(p, m.v.get(t[0]), m.v.get(t[1]), m.v.get(t[2]));
    const double d = (q - p).squaredNorm();
    if (d < bd) {
      bd = d;
      best = q;
    }
  }
  return best;
}

int nearest_of(const Points& v, const std::vector<int>& allowed, const Vec3& p) {
  int best = -1;
  double bd = kInf;
  auto consider = [&](int i) {
    const double d = (v.get(i) - p).squaredNorm();
    if (d < bd) {
      bd = d;
      best = i;
    }
  };
  if (allowed.empty())
    for (int i = 0; i < static_cast<int>(v.size()); ++i) consider(i);
  else
    for (int i : allowed) consider(i);
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

// Vertices from a to b along mesh edges (a first, b excluded); empty when unreachable.
std::vector<int> edge_path(const Points& v, const Adjacency& adj, int a, int b) {
  const std::vector<double> d = edge_geodesic(v, adj, {b});
  if (!std::isfinite(d[a])) return {};
  std::vector<int> path;
  for (int u = a; u != b;) {
    path.push_back(u);
    int next = -1;
    double nd = kInf;
    for (int k = adj.start[u]; k < adj.start[u + 1]; ++k) {
      const int w = adj.nbr[k];
      const double c = d[w] + (v.get(u) - v.get(w)).norm();
      if (c < nd) {
        nd = c;
        next = w;
      }
    }
    u = next;
  }
  return path;
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

void check_head_mesh(const TriMesh& m, const std::string& what) {
  constexpr std::size_t kMinVertices = 100;
  if (m.v.size() < kMinVertices)
    throw InputError(what + ": expected a face mesh of at least " + std::to_string(kMinVertices) +
                     " vertices, found " + std::to_string(m.v.size()));
  std::size_t used = 0, good = 0;
  std::vector<char> referenced(m.v.size(), 0);
  for (const Tri& t : m.tris) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw InputError(what + ": a face uses vertex " + std::to_string(t[0] + 1) +
                       " twice (degenerate)");
    for (int i : t) referenced[i] = 1;
    const Vec3 n = (m.v.get(t[1]) - m.v.get(t[0])).cross(m.v.get(t[2]) - m.v.get(t[0]));
    if (n.norm() > 0) ++good;
  }
  for (char r : referenced) used += r;
  if (used < kMinVertices)
    throw InputError(what + ": expected faces over at least " + std::to_string(kMinVertices) +
                     " vertices, found " + std::to_string(used));
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

HeadFit fit_head(const HeadSpec& source, const TriMesh& source_skin, const TriMesh& target,
                 const HeadFitOptions& o) {
  HeadFit fit;
  const Points& S = source_skin.v;
  const Points& T = target.v;

  // Initial alignment: per-axis scale and centre from the bounding boxes (both face +z).
  const Box bs = box_of(S), bt = box_of(T);
  const Vec3 scale = bt.size().cwiseQuotient(bs.size());
  auto initial = [&](const Vec3& p) -> Vec3 {
    return bt.centre() + scale.cwiseProduct(p - bs.centre());
  };
  fit.size_ratio = std::sqrt(scale.x() * scale.y());

  // Openings the target already has as holes: the boundary loop near each source contour
  // (after the initial alignment), ordered like the source's own loop.
  const auto loops = boundary_loops(target.tris);
  std::vector<OpeningLoops> holes(source.openings.size());
  std::vector<int> on_contour(S.size(), -1);  // source vertex → index of its opening
  for (std::size_t oi = 0; oi < source.openings.size(); ++oi) {
    const auto& verts = source.openings[oi].second;
    for (int v : verts) on_contour[v] = static_cast<int>(oi);
    holes[oi].source = source_loop(source_skin, verts);
    std::vector<Vec3> mapped;
    Box mb;
    for (int v : verts) {
      mapped.push_back(closest_on_mesh(target, initial(S.get(v))));
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

  // Correspondences: every skin landmark vertex and every contour vertex of an opening the
  // target has as a hole, plus a spread sample of the skin.
  // Surface points near such a rim are left to G: the rim carries them, where a closest
  // point would slide across the curved lips (measured: outer lip corners 4.6 mm off).
  std::vector<int> rim;
  for (const OpeningLoops& h : holes)
    if (!h.target.empty()) rim.insert(rim.end(), h.source.begin(), h.source.end());
  auto near_rim = [&](int v) {
    for (int r : rim)
      if (r != v && (S.get(r) - S.get(v)).norm() < o.rim_reach) return true;
    return false;
  };
  std::vector<int> corr;
  for (const LandmarkSpec& l : source.landmarks)
    for (int v : l.vertices)
      if (!near_rim(v) || on_contour[v] >= 0) corr.push_back(v);
  for (const OpeningLoops& h : holes)
    if (!h.target.empty()) corr.insert(corr.end(), h.source.begin(), h.source.end());
  std::sort(corr.begin(), corr.end());
  corr.erase(std::unique(corr.begin(), corr.end()), corr.end());
  for (int v : spread_samples(S, corr, o.surface_samples))
    if (!near_rim(v)) corr.push_back(v);
  std::vector<Vec3> from(corr.size()), to(corr.size()), prev(corr.size(), Vec3::Zero());
  std::map<int, std::size_t> corr_index;
  for (std::size_t k = 0; k < corr.size(); ++k) {
    from[k] = S.get(corr[k]);
    corr_index[corr[k]] = k;
  }

  // Non-rigid fit. Surface points go to the closest target point; contour points of a hole
  // to the same share of arc length along the target's loop (closest points would let
  // them slide along the rim, and G interpolates them, so nothing would correct it).
  // G changes the closest points, and the rim alignment; repeat until they stop moving.
  auto morph = [&](const Vec3& p) { return fit.iterations == 0 ? initial(p) : fit.morph.apply(p); };
  for (int it = 0; it < o.max_iterations; ++it) {
    for (std::size_t k = 0; k < corr.size(); ++k) to[k] = closest_on_mesh(target, morph(from[k]));
    for (const OpeningLoops& h : holes) {
      if (h.target.empty()) continue;
      std::vector<Vec3> mapped;
      for (int v : h.source) mapped.push_back(morph(S.get(v)));
      const std::vector<Vec3> on_rim = along_loop(S, h.source, T, h.target, mapped);
      for (std::size_t i = 0; i < h.source.size(); ++i) to[corr_index[h.source[i]]] = on_rim[i];
    }
    double change = 0;
    for (std::size_t k = 0; k < prev.size(); ++k)
      change = std::max(change, (to[k] - prev[k]).norm());
    fit.morph = fit_rbf(from, to);
    prev = to;
    fit.iterations = it + 1;
    fit.last_change_mm = change * 1e3;
    // Refinement (thesis ch. 6): the source vertices the morph leaves farthest from the
    // target surface become correspondences too.
    std::vector<std::pair<double, int>> gap;
    for (int v = 0; v < static_cast<int>(S.size()); ++v) {
      if (corr_index.count(v) || near_rim(v)) continue;
      const Vec3 p = fit.morph.apply(S.get(v));
      const double d = (closest_on_mesh(target, p) - p).norm();
      if (d * 1e3 > o.refine_above_mm) gap.push_back({d, v});
    }
    std::sort(gap.rbegin(), gap.rend());
    gap.resize(std::min<std::size_t>(gap.size(), static_cast<std::size_t>(o.worst_pairs)));
    for (const auto& g : gap) {
      corr_index[g.second] = corr.size();
      corr.push_back(g.second);
      from.push_back(S.get(g.second));
      to.push_back(Vec3::Zero());
    }
    fit.refined_pairs += static_cast<int>(gap.size());
    if (it > 0 && gap.empty() && fit.last_change_mm < o.converged_mm) break;
  }
  const RbfMorph& G = fit.morph;

  // Openings: the hole found above, else the mapped contour snapped to target vertices and
  // joined by shortest edge paths.
  const Adjacency adj = vertex_adjacency(T.size(), target.tris);
  std::map<std::string, std::vector<int>> opening_of;
  fit.spec = source;
  fit.spec.openings.clear();
  for (std::size_t oi = 0; oi < source.openings.size(); ++oi) {
    const auto& [name, verts] = source.openings[oi];
    std::vector<Vec3> mapped;
    for (int v : verts) mapped.push_back(closest_on_mesh(target, G.apply(S.get(v))));
    const std::vector<int>& best_loop = holes[oi].target;
    std::vector<int> contour;
    if (!best_loop.empty()) {
      contour = best_loop;
      fit.opening_notes.push_back(name + ": the mesh's own hole (" +
                                  std::to_string(contour.size()) + " vertices)");
    } else {
      std::vector<int> snapped;
      for (const Vec3& p : mapped) {
        const int s = nearest_of(T, {}, p);
        if (snapped.empty() || snapped.back() != s) snapped.push_back(s);
      }
      bool closed = snapped.size() >= 3;
      for (std::size_t k = 0; closed && k < snapped.size(); ++k) {
        auto part = edge_path(T, adj, snapped[k], snapped[(k + 1) % snapped.size()]);
        if (part.empty()) closed = false;
        for (int v : part)
          if (std::find(contour.begin(), contour.end(), v) == contour.end()) contour.push_back(v);
      }
      if (!closed) {
        fit.problems.push_back("opening " + name + ": could not close a contour on the mesh");
        contour.clear();
      } else {
        fit.opening_notes.push_back(name + ": contour of " + std::to_string(contour.size()) +
                                    " vertices joined along edges (mesh closed there)");
      }
    }
    opening_of[name] = contour;
    fit.spec.openings.push_back({name, contour});
  }

  // Landmarks: each source vertex mapped by G and snapped (contour vertices to the
  // matching target contour); bone points keep G's position through a new offset.
  const double edge = median_edge(target);
  std::map<std::string, Vec3> src_pos, new_pos;
  for (std::size_t li = 0; li < source.landmarks.size(); ++li) {
    const LandmarkSpec& l = source.landmarks[li];
    LandmarkSpec& nl = fit.spec.landmarks[li];
    PlacedLandmark p;
    p.name = l.name;
    p.bone = l.offset.norm() > 0;
    Vec3 src = Vec3::Zero();
    for (int v : l.vertices) src += S.get(v);
    src = src / static_cast<double>(l.vertices.size()) + l.offset;
    src_pos[l.name] = src;
    p.fitted = G.apply(src);
    p.initial_mm = (closest_on_mesh(target, initial(src)) - initial(src)).norm() * 1e3;
    nl.vertices.clear();
    Vec3 mean = Vec3::Zero();
    for (int v : l.vertices) {
      const Vec3 q = G.apply(S.get(v));
      const int oi = on_contour[v];
      const std::vector<int>* allowed = nullptr;
      if (oi >= 0) allowed = &opening_of[source.openings[oi].first];
      const int t = nearest_of(T, allowed && !allowed->empty() ? *allowed : std::vector<int>{}, q);
      nl.vertices.push_back(t);
      mean += T.get(t);
    }
    mean /= static_cast<double>(nl.vertices.size());
    p.vertices = nl.vertices;
    p.offset = p.bone ? Vec3(p.fitted - mean) : Vec3::Zero();
    nl.offset = p.offset;
    p.snap_mm = (mean + p.offset - p.fitted).norm() * 1e3;
    new_pos[l.name] = mean + p.offset;
    if (!p.bone && p.snap_mm > o.max_snap_edges * edge * 1e3 && l.vertices.size() == 1)
      fit.problems.push_back("landmark " + l.name + ": nearest vertex " + mm(p.snap_mm * 1e-3) +
                             " away (more than " + std::to_string(o.max_snap_edges) +
                             " median edges of " + mm(edge) + ")");
    fit.landmarks.push_back(p);
  }

  // A face, the right way round: catches meshes with nothing face-like, or facing −z.
  auto at = [&](const char* n) { return new_pos.count(n) ? new_pos[n] : Vec3(Vec3::Zero()); };
  if (new_pos.count("fdp_3_7") && new_pos.count("fdp_3_8") && new_pos.count("fdp_9_3") &&
      new_pos.count("fdp_2_2")) {
    const Vec3 eyes = 0.5 * (at("fdp_3_7") + at("fdp_3_8"));
    if (!(at("fdp_3_7").x() > at("fdp_3_8").x()))
      fit.problems.push_back("the fitted left eye (fdp_3_7) is not at +x of the right (fdp_3_8)");
    if (!(eyes.y() > at("fdp_2_2").y()))
      fit.problems.push_back("the fitted eyes are not above the mouth (y up?)");
    if (!(at("fdp_9_3").z() > eyes.z()))
      fit.problems.push_back("the fitted nose tip (fdp_9_3) is not in front of the eyes (+z?)");
  }

  // Muscle corners: source landmark + offset, carried by G, as new landmark + offset.
  for (MuscleSpec& m : fit.spec.muscles)
    for (auto* refs : {&m.origin, &m.insertion, &m.inner, &m.outer})
      for (PointRef& r : *refs)
        r.offset = G.apply(src_pos[r.landmark] + r.offset) - new_pos[r.landmark];

  // Lengths that scale with the head; variants are for the user to choose.
  HeadSpec& h = fit.spec;
  const double s = fit.size_ratio;
  h.tissue_depth *= s;
  // The teeth and eyeballs follow the mouth's and the eyes' own widths: a jaw narrower
  // than the bounding box would otherwise push the lip corners onto too wide an arch.
  auto width_ratio = [&](const char* a, const char* b) {
    if (!src_pos.count(a) || !src_pos.count(b)) return s;
    return (new_pos[a] - new_pos[b]).norm() / (src_pos[a] - src_pos[b]).norm();
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
  return fit;
}

}  // namespace facectl::face
