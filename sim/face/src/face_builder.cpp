// Pre-processing of thesis §5.4–§5.6: openings, skull and mandible, teeth, muscles on
// their support layers, skin binding by ray casting, influence map and eyelids.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "facectl/face/face_model.hpp"
#include "facectl/face/head_fit.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/obj_io.hpp"
#include "facectl/face/subdivision.hpp"
#include "skin_anchors.hpp"

namespace facectl::face {
namespace {

struct Support {
  Layer layer;
  const Points* pts;
  std::vector<Tri> tris;
};

TriMesh cut_openings(TriMesh m, const HeadSpec& spec) {
  for (const auto& [name, verts] : spec.openings) {
    for (int v : verts)
      if (v < 0 || v >= static_cast<int>(m.v.size()))
        throw InputError(spec.dir + "/face.yaml: openings." + name + ": vertex " +
                         std::to_string(v) + " is outside the skin's 0.." +
                         std::to_string(m.v.size() - 1));
    std::vector<char> in(m.v.size(), 0);
    for (int v : verts) in[v] = 1;
    std::erase_if(m.tris, [&](const Tri& t) { return in[t[0]] && in[t[1]] && in[t[2]]; });
  }
  return m;
}

int nearest_vertex(const Points& v, const Vec3& p) {
  int best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) {
    double d = (v.get(i) - p).squaredNorm();
    if (d < bd) {
      bd = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

// The skin's normal at the point of the skin closest to p, interpolated across that
// triangle from its vertex normals. The muscles are cast and thickened along it: the
// nearest vertex's normal is constant around each vertex and jumps between them, and a
// jump under a muscle line set its two mirror halves millimetres apart.
Vec3 smooth_normal(const TriMesh& skin, const Points& normals, const Vec3& p) {
  const MeshPoint on = closest_on_mesh(skin, p);
  const Tri& best = skin.tris[static_cast<std::size_t>(on.triangle)];
  const Vec3 q = on.point;
  const Vec3 a = skin.v.get(best[0]), e1 = skin.v.get(best[1]) - a, e2 = skin.v.get(best[2]) - a;
  const Vec3 r = q - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double den = d11 * d22 - d12 * d12;
  if (!(den > 0)) return normals.get(best[0]);
  const double v = (d22 * r.dot(e1) - d12 * r.dot(e2)) / den;
  const double w = (d11 * r.dot(e2) - d12 * r.dot(e1)) / den;
  const Vec3 n =
      (1 - v - w) * normals.get(best[0]) + v * normals.get(best[1]) + w * normals.get(best[2]);
  return n.normalized();
}

// Nearest hit along the line p + t·dir over the supports, with t in [tmin, tmax],
// preferring the smallest |t|. Returns false if nothing is hit.
bool cast(const std::vector<Support>& supports, const Vec3& p, const Vec3& dir, double tmin,
          double tmax, SurfacePoint& out) {
  double best = std::numeric_limits<double>::infinity();
  for (const Support& s : supports)
    for (const Tri& t : s.tris) {
      double u, v;
      double hit = ray_triangle(p, dir, s.pts->get(t[0]), s.pts->get(t[1]), s.pts->get(t[2]), u, v);
      if (u < -1e-9 || hit < tmin || hit > tmax || std::abs(hit) >= best) continue;
      // ray_triangle returns −1 for a miss; a true hit at t = −1 m is out of range anyway.
      best = std::abs(hit);
      out = {s.layer,         t[0], t[1], t[2], std::max(0.0, 1 - u - v), std::max(0.0, u),
             std::max(0.0, v)};
    }
  return best < std::numeric_limits<double>::infinity();
}

SurfacePoint vertex_point(Layer layer, const std::vector<Tri>& tris, int v) {
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k)
      if (t[k] == v) return {layer, t[k], t[(k + 1) % 3], t[(k + 2) % 3], 1, 0, 0};
  return {layer, v, v, v, 1, 0, 0};
}

double smoothstep01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

Vec3 mean_plus_offset(const std::vector<int>& vertices, const Vec3& offset, const Points& skin) {
  Vec3 s = Vec3::Zero();
  for (int v : vertices) s += skin.get(v);
  return s / static_cast<double>(vertices.size()) + offset;
}

void check_landmark_vertices(const LandmarkSpec& l, int nbase) {
  for (int v : l.vertices)
    if (v < 0 || v >= nbase)
      throw InputError(l.file, l.line, l.column,
                       "landmark '" + l.name + "': expected vertices of the skin, 0.." +
                           std::to_string(nbase - 1) + ", found vertex " + std::to_string(v));
}

}  // namespace

int FaceModel::landmark_index(const std::string& name) const {
  for (std::size_t i = 0; i < landmark_names.size(); ++i)
    if (landmark_names[i] == name) return static_cast<int>(i);
  return -1;
}

std::vector<int> FaceModel::landmark_indices(const std::vector<std::string>& names) const {
  std::vector<int> indices;
  indices.reserve(names.size());
  for (const std::string& n : names) indices.push_back(landmark_index(n));
  return indices;
}

Vec3 landmark_position(const FaceModel& m, const Points& skin, int l) {
  return mean_plus_offset(m.landmark_vertices[l], m.landmark_offset[l], skin);
}

Vec3 landmark_position(const LandmarkSpec& l, const Points& skin) {
  check_landmark_vertices(l, static_cast<int>(skin.size()));
  return mean_plus_offset(l.vertices, l.offset, skin);
}

TriMesh read_base_skin(const HeadSpec& spec) {
  return cut_openings(read_obj(spec.skin_file, spec.skin_scale), spec);
}

namespace {

// A landmark's rest position on the base skin, by name; a missing one is an error.
struct Landmarks {
  const FaceModel& m;
  const Points& base;
  const HeadSpec& spec;
  Vec3 operator()(const std::string& name) const {
    int i = m.landmark_index(name);
    if (i < 0) throw InputError(spec.dir + "/landmarks.yaml: missing landmark '" + name + "'");
    return landmark_position(m, base, i);
  }
};

void bind_landmarks(const HeadSpec& spec, int nbase, FaceModel& m) {
  for (const LandmarkSpec& l : spec.landmarks) {
    check_landmark_vertices(l, nbase);
    m.landmark_names.push_back(l.name);
    m.landmark_vertices.push_back(l.vertices);
    m.landmark_offset.push_back(l.offset);
  }
}

// Skull: the skin pushed inward by the soft-tissue depth; same topology. Mandible:
// skull below the plane through the condyles and the stomion. Returns the stomion.
Vec3 build_skull(const HeadSpec& spec, const TriMesh& base, const Points& base_n,
                 const Landmarks& L, FaceModel& m) {
  const int nbase = static_cast<int>(base.v.size());
  m.skull = base;
  for (int i = 0; i < nbase; ++i)
    m.skull.v.set(i, base.v.get(i) - spec.tissue_depth * base_n.get(i));
  m.axes = mandible_axes(L("fdp_2_13"), L("fdp_2_14"), L("fdp_11_4"), L("fdp_7_1"), L("fdp_2_10"));
  const Vec3 stomion = 0.5 * (L("fdp_2_2") + L("fdp_2_3"));
  Vec3 split_n = m.axes.pitch_axis.cross(stomion - m.axes.yaw_point).normalized();
  if (split_n.y() < 0) split_n = -split_n;
  for (int i = 0; i < nbase; ++i)
    if (split_n.dot(m.skull.v.get(i) - m.axes.yaw_point) < 0) m.mandible_vertices.push_back(i);
  return stomion;
}

// Teeth: two parabolic arches behind the stomion, split by the occlusal plane.
void build_teeth(const HeadSpec& spec, const Vec3& stomion, FaceModel& m) {
  std::vector<Vec3> up, lo;
  const Vec3 front = stomion - Vec3(0, 0, spec.teeth_inset);
  for (int j = 0; j <= 8; ++j) {
    const double s = -1 + j / 4.0;
    const Vec3 a = front + Vec3(s * spec.teeth_half_width, 0, -spec.teeth_depth * s * s);
    up.push_back(a + Vec3(0, spec.teeth_gap / 2, 0));
    up.push_back(a + Vec3(0, spec.teeth_gap / 2 + spec.teeth_height, 0));
    lo.push_back(a - Vec3(0, spec.teeth_gap / 2, 0));
    lo.push_back(a - Vec3(0, spec.teeth_gap / 2 + spec.teeth_height, 0));
  }
  m.upper_teeth = convex_hull(up);
  m.lower_teeth = convex_hull(lo);
}

void group_muscle_layers(const std::vector<std::vector<Tri>>& tops, FaceModel& m);

// Muscles, deepest first, each resting on the skull and on the layers already built;
// then their constraints grouped by layer. Returns the top triangles of each muscle.
std::vector<std::vector<Tri>> build_muscles(const HeadSpec& spec, const TriMesh& base,
                                            const Points& base_n, const Landmarks& L,
                                            FaceModel& m) {
  std::vector<MuscleSpec> order = spec.muscles;
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.layer < b.layer; });
  std::vector<Support> supports{{Layer::kSkull, &m.skull.v, m.skull.tris}};
  std::vector<std::vector<Tri>> tops;  // top triangles of each built muscle
  auto resolve = [&](const PointRef& r) -> Vec3 { return L(r.landmark) + r.offset; };
  auto project = [&](const Vec3& p, int layer) {
    const Vec3 n = smooth_normal(base, base_n, p);
    std::vector<Support> below{supports[0]};
    for (std::size_t k = 0; k < m.muscles.size(); ++k)
      if (m.muscles[k].layer < layer) below.push_back({Layer::kMuscle, &m.muscle_rest, tops[k]});
    SurfacePoint sp;
    // From outside the skin inward, so the first surface met is the most superficial.
    if (cast(below, p + 0.03 * n, -n, 0, 0.03 + 3 * spec.tissue_depth, sp)) return sp;
    return vertex_point(Layer::kSkull, m.skull.tris, nearest_vertex(m.skull.v, p));
  };
  for (const MuscleSpec& ms : order) {
    Muscle mu;
    mu.name = ms.name;
    mu.kind = ms.kind;
    mu.layer = ms.layer;
    mu.rows = ms.rows;
    mu.cols = ms.cols;
    if (ms.kind == MuscleKind::kSheet) {
      const int segs = 8;
      for (int c = 0; c < ms.cols; ++c) {
        const double f = static_cast<double>(c) / (ms.cols - 1);
        Vec3 o = (1 - f) * resolve(ms.origin[0]) + f * resolve(ms.origin[1]);
        Vec3 i = (1 - f) * resolve(ms.insertion[0]) + f * resolve(ms.insertion[1]);
        std::vector<SurfacePoint> line;
        for (int j = 0; j <= segs; ++j)
          line.push_back(project(o + (i - o) * (j / double(segs)), ms.layer));
        mu.lines.push_back(line);
      }
    } else {
      for (const auto* ring : {&ms.inner, &ms.outer}) {
        std::vector<SurfacePoint> line;
        const std::size_t n = ring->size();
        for (std::size_t k = 0; k < n; ++k) {
          Vec3 a = resolve((*ring)[k]), b = resolve((*ring)[(k + 1) % n]);
          for (int j = 0; j < 3; ++j) line.push_back(project(a + (b - a) * (j / 3.0), ms.layer));
        }
        mu.lines.push_back(line);
      }
    }
    place_muscle(
        mu, ms.thickness, [&](const Vec3& p) { return smooth_normal(base, base_n, p); }, m.skull.v,
        m.muscle_rest, ms.kind == MuscleKind::kSheet ? spec.sheet : spec.sphincter);
    const int nb = mu.rows * mu.cols;
    std::vector<Tri> top;
    for (const Tri& t : mu.surface)
      if (t[0] >= mu.first + nb && t[1] >= mu.first + nb && t[2] >= mu.first + nb) top.push_back(t);
    tops.push_back(top);
    int slot = -1;
    for (std::size_t k = 0; k < spec.commanded.size(); ++k)
      if (spec.commanded[k] == ms.name) slot = static_cast<int>(k);
    m.command_slot.push_back(slot);
    m.is_oculi.push_back(ms.name == "orbicularis_oculi_l"   ? 0
                         : ms.name == "orbicularis_oculi_r" ? 1
                                                            : 2);
    m.muscles.push_back(std::move(mu));
  }
  group_muscle_layers(tops, m);
  return tops;
}

// The muscles' constraints grouped by layer (a layer is projected as one sweep), and
// the top surface the skin binds to.
void group_muscle_layers(const std::vector<std::vector<Tri>>& tops, FaceModel& m) {
  m.muscle_w.assign(m.muscle_rest.size(), 1.0);
  for (std::size_t k = 0; k < m.muscles.size(); ++k) {
    if (k == 0 || m.muscles[k].layer != m.muscles[k - 1].layer)
      m.muscle_layers.push_back({static_cast<int>(k), static_cast<int>(k), {}, {}});
    FaceModel::MuscleLayer& ml = m.muscle_layers.back();
    ml.end = static_cast<int>(k) + 1;
    append(ml.distances, m.muscles[k].distances);
    append(ml.bending, m.muscles[k].bending);
  }
  for (FaceModel::MuscleLayer& ml : m.muscle_layers) {
    order_in_runs(ml.distances, m.muscle_rest);
    order_in_runs(ml.bending, m.muscle_rest);
  }
  for (const auto& t : tops) m.muscle_tops.insert(m.muscle_tops.end(), t.begin(), t.end());
  vertex_normals(m.muscle_rest, m.muscle_tops, m.muscle_rest_normals);
}

// Skin binding: along the vertex normal line, the nearest muscle top (outward hits
// allowed: fitted muscles may poke out), else the skull, else the nearest skull vertex.
// The anchor is carried in the support triangle's frame. Returns the vertices bound to
// muscles or the jaw (where the influence map is 1).
std::vector<int> bind_skin(const HeadSpec& spec, const Points& skin_n, int nbase,
                           const std::vector<std::vector<Tri>>& tops, FaceModel& m) {
  const int ns = static_cast<int>(m.skin.v.size());
  std::vector<Support> muscle_tops;
  for (std::size_t k = 0; k < m.muscles.size(); ++k)
    muscle_tops.push_back({Layer::kMuscle, &m.muscle_rest, tops[k]});
  std::vector<Support> skull_only{{Layer::kSkull, &m.skull.v, m.skull.tris}};
  std::vector<char> on_jaw(nbase, 0);
  for (int v : m.mandible_vertices) on_jaw[v] = 1;
  std::vector<int> seeds;
  int max_layer = 0;
  for (const Muscle& mu : m.muscles) max_layer = std::max(max_layer, mu.layer);
  m.anchor_local.resize(ns);
  // The anchor stiffness is per unit skin area: a vertex of a finer variant holds a smaller
  // share of the skin, so its anchor is weaker in proportion (k · nbase/ns), and the balance
  // between the anchors and the edge network, which keeps its per-edge stiffness, stays
  // that of the base mesh. With the same k on every variant the finer skins followed their
  // anchors more and their neighbours less, and most library expressions did not settle on
  // them (face_convergence_probe resolution).
  const double anchor_k = spec.skin.anchor * nbase / ns;
  for (int i = 0; i < ns; ++i) {
    const Vec3 p = m.skin.v.get(i), n = skin_n.get(i);
    SurfacePoint sp;
    const double reach = spec.tissue_depth;
    // Muscles are tested from the most superficial layer down, then the skull.
    bool hit = false;
    for (int layer = max_layer; layer >= 0 && !hit; --layer) {
      std::vector<Support> in_layer;
      for (std::size_t k = 0; k < m.muscles.size(); ++k)
        if (m.muscles[k].layer == layer) in_layer.push_back(muscle_tops[k]);
      hit = cast(in_layer, p, -n, -0.5 * reach, reach, sp);
    }
    if (!hit && !cast(skull_only, p, -n, -0.5 * reach, 3 * reach, sp))
      sp = vertex_point(Layer::kSkull, m.skull.tris, nearest_vertex(m.skull.v, p));
    const Mat3 F = sp.layer == Layer::kSkull
                       ? sp.frame(m.skull.v)
                       : sp.smooth_frame(m.muscle_rest, m.muscle_rest_normals);
    const Points& src = sp.layer == Layer::kSkull ? m.skull.v : m.muscle_rest;
    m.anchor_local.set(i, F.transpose() * (p - sp.position(src)));
    m.anchor_support.push_back(sp);
    m.anchors.add(i, anchor_k);
    const bool jaw = sp.layer == Layer::kSkull && (on_jaw[sp.i0] || on_jaw[sp.i1] || on_jaw[sp.i2]);
    (sp.layer == Layer::kMuscle ? m.anchors_on_muscles
     : jaw                      ? m.anchors_on_jaw
                                : m.anchors_on_fixed_skull)
        .push_back(i);
    if (sp.layer == Layer::kMuscle || jaw) seeds.push_back(i);
  }
  return seeds;
}

// Skin constraints (k_stretching, k_bending, k_area, k_volume), and the upright
// constraints indexed by vertex.
void build_skin_constraints(const HeadSpec& spec, FaceModel& m) {
  const int ns = static_cast<int>(m.skin.v.size());
  m.skin_w.assign(ns, 1.0);
  add_edge_distances(m.skin_stretch, m.skin.v, m.skin.tris, spec.skin.stretch);
  add_bending(m.skin_bending, m.skin.v, m.skin.tris, spec.skin.bending);
  // An interior edge's stretch is projected with its bending pair (fused sweep).
  m.skin_pair_stretch = split_pair_stretch(m.skin_stretch, m.skin_bending, m.skin.v);
  add_areas(m.skin_area, m.skin.v, m.skin.tris, spec.skin.area);
  add_orientations(m.skin_upright, m.skin.v, m.skin.tris, spec.skin.min_projected_area, 1.0);
  Adjacency& ua = m.upright_of_vertex;
  ua.start.assign(ns + 1, 0);
  const OrientationConstraints& o = m.skin_upright;
  for (const auto* v : {&o.a, &o.b, &o.c})
    for (int i : *v) ++ua.start[i + 1];
  for (int i = 0; i < ns; ++i) ua.start[i + 1] += ua.start[i];
  ua.nbr.resize(ua.start[ns]);
  std::vector<int> fill(ua.start.begin(), ua.start.end() - 1);
  for (std::size_t c = 0; c < o.size(); ++c)
    for (int v : {o.a[c], o.b[c], o.c[c]}) ua.nbr[fill[v]++] = static_cast<int>(c);
  m.skin_volume = make_volume(m.skin.v, m.skin.tris, m.axes.yaw_point, spec.skin.volume);
}

// Eyelids (thesis §5.5.1): vertices near each eye opening's border, rotated rigidly
// about an axis parallel to the eye corners through the eyeball centre.
void build_eyelids(const HeadSpec& spec, const Landmarks& L, const Adjacency& adj, FaceModel& m) {
  const int ns = static_cast<int>(m.skin.v.size());
  const auto loops = boundary_loops(m.skin.tris);
  const char* upper_lm[2] = {"fdp_3_1", "fdp_3_2"};
  const char* lower_lm[2] = {"fdp_3_3", "fdp_3_4"};
  const char* outer_lm[2] = {"fdp_3_7", "fdp_3_8"};
  const char* inner_lm[2] = {"fdp_3_11", "fdp_3_12"};
  for (int side = 0; side < 2; ++side) {
    const int lid_vertex = m.landmark_vertices[m.landmark_index(upper_lm[side])][0];
    std::vector<int> border;
    for (const auto& loop : loops)
      if (std::find(loop.begin(), loop.end(), lid_vertex) != loop.end()) border = loop;
    if (border.empty())
      throw InputError(spec.dir + "/face.yaml: no eye opening contains landmark " + upper_lm[side]);
    const Vec3 co = L(outer_lm[side]), ci = L(inner_lm[side]);
    EyelidSide& e = m.eyes[side];
    e.axis = (ci - co).normalized();
    e.axis_point = 0.5 * (co + ci) - Vec3(0, 0, spec.eyeball_radius);
    auto perp = [&](const Vec3& p) {
      Vec3 d = p - e.axis_point;
      return Vec3(d - e.axis * e.axis.dot(d));
    };
    const Vec3 u = perp(L(upper_lm[side])), d = perp(L(lower_lm[side]));
    const double phi = std::atan2(e.axis.dot(u.cross(d)), u.dot(d));
    e.upper_max = spec.upper_lid_share * phi;
    e.lower_max = -(1 - spec.upper_lid_share) * phi;
    const Vec3 split = e.axis.cross(Vec3::UnitZ());
    const double upper_sign = split.dot(u) > 0 ? 1 : -1;
    const std::vector<double> g = edge_geodesic(m.skin.v, adj, border);
    for (int i = 0; i < ns; ++i)
      if (g[i] < spec.eyelid_band) {
        m.lids.add(i, 1.0);  // infinite-mass drivers: the particle takes the driver's place
        m.lid_side.push_back(static_cast<std::uint8_t>(side));
        m.lid_upper.push_back(split.dot(perp(m.skin.v.get(i))) * upper_sign > 0);
        m.lid_rest.push_back(m.skin.v.get(i));
        // The opening is highest mid-eye and closes to nothing at the corners; scaling the
        // angle by sin(π·s) makes the margins meet along their length instead of crossing
        // near the corners.
        const double along =
            std::clamp((m.skin.v.get(i) - co).dot(ci - co) / (ci - co).squaredNorm(), 0.0, 1.0);
        m.lid_profile.push_back(std::sin(std::numbers::pi * along));
      }
  }
}

// A muscle's name is its command slot and, for orbicularis_oculi_l/_r, the eyelid it
// closes: two of one name would share the slot, and the lid would follow only one of them.
// load_head_spec refuses them with the line; this refuses a spec assembled in code.
void check_unique_muscle_names(const HeadSpec& spec) {
  std::map<std::string, int> seen;
  for (const MuscleSpec& ms : spec.muscles)
    if (++seen[ms.name] == 2)
      throw InputError(spec.dir + ": two muscles are named '" + ms.name +
                       "'; each muscle needs its own name");
}

}  // namespace

FaceModel build_face_model(const HeadSpec& spec, std::size_t skin_vertices) {
  check_unique_muscle_names(spec);
  FaceModel m;
  m.spec = spec;
  const TriMesh base = read_base_skin(spec);
  const int nbase = static_cast<int>(base.v.size());
  Points base_n;
  vertex_normals(base.v, base.tris, base_n);
  bind_landmarks(spec, nbase, m);
  const Landmarks L{m, base.v, spec};

  const Vec3 stomion = build_skull(spec, base, base_n, L, m);
  build_teeth(spec, stomion, m);

  // Skin (possibly refined; base vertex indices are preserved).
  m.skin = skin_vertices > base.v.size() ? refine_to_vertex_count(base, skin_vertices).mesh : base;
  const int ns = static_cast<int>(m.skin.v.size());
  Points skin_n;
  vertex_normals(m.skin.v, m.skin.tris, skin_n);

  const std::vector<std::vector<Tri>> tops = build_muscles(spec, base, base_n, L, m);
  const std::vector<int> seeds = bind_skin(spec, skin_n, nbase, tops, m);

  // Influence map: 1 on vertices bound to muscles or the jaw, easing to 0 over
  // `influence_falloff` of edge-geodesic distance.
  const Adjacency adj = vertex_adjacency(ns, m.skin.tris);
  const std::vector<double> geo = edge_geodesic(m.skin.v, adj, seeds);
  m.influence.resize(ns);
  for (int i = 0; i < ns; ++i) m.influence[i] = 1 - smoothstep01(geo[i] / spec.influence_falloff);

  build_skin_constraints(spec, m);
  build_eyelids(spec, L, adj, m);
  return m;
}

FaceData make_face_data(const FaceModel& m) {
  FaceData d;
  const std::size_t ns = m.skin.v.size();
  d.anchor_targets.resize(ns);
  reset_face_data(m, d);
  d.grad.resize(std::max(ns, m.muscle_rest.size()));
  std::size_t max_line = 0, max_grid = 0;
  for (const Muscle& mu : m.muscles) {
    for (const auto& l : mu.lines) max_line = std::max(max_line, l.size());
    max_grid = std::max<std::size_t>(max_grid, static_cast<std::size_t>(mu.rows * mu.cols));
  }
  d.scratch = make_muscle_scratch(max_line, max_grid);
  d.contraction.assign(m.muscles.size(), 0.0);
  d.hit_particle.assign(ns, 0);
  d.untangle_list.assign(m.skin_upright.size(), 0);
  d.untangle_next.assign(m.skin_upright.size(), 0);
  d.vertex_mark.assign(ns, 0);
  d.upright_mark.assign(m.skin_upright.size(), 0);
  d.hit_target.resize(ns);
  return d;
}

void reset_face_data(const FaceModel& m, FaceData& d) {
  d.skin_x = m.skin.v;
  d.skin_prev = m.skin.v;
  d.skin_p = m.skin.v;
  d.skull = m.skull.v;
  d.muscles = m.muscle_rest;
  d.muscles_before = m.muscle_rest;
  d.muscle_normals = m.muscle_rest_normals;
  d.lid_targets = m.lid_rest;
  d.lower_teeth = m.lower_teeth;
  d.hits = 0;
  d.frame = 0;
  set_fixed_anchor_targets(m, d);
}

}  // namespace facectl::face
