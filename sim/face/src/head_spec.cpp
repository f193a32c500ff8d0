#include "facectl/face/head_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>

#include "facectl/face/input_error.hpp"
#include "facectl/face/yaml_file.hpp"

namespace facectl::face {
namespace {

constexpr int kMaxSkinIterations = 100;
constexpr int kMaxGrid = 64;  // grid points per side of a muscle; the shipped ones use 2..16

struct Doc {
  std::string file;
  YAML::Node root;
};

Doc load(const std::string& file) {
  return {file, load_yaml_file(file)};
}

[[noreturn]] void fail(const Doc& d, const YAML::Node& n, const std::string& key,
                       const std::string& expected) {
  std::string found = !n.IsDefined()   ? "nothing"
                      : n.IsScalar()   ? "'" + n.Scalar() + "'"
                      : n.IsSequence() ? "a list"
                      : n.IsMap()      ? "a mapping"
                                       : "null";
  int line = n.IsDefined() ? n.Mark().line + 1 : 0, col = n.IsDefined() ? n.Mark().column + 1 : 0;
  throw InputError(d.file, line, col,
                   "key '" + key + "': expected " + expected + ", found " + found);
}

// A key the reader does not know is an error at its line, not a setting quietly ignored:
// a misspelt stiffness or tooth size would otherwise build another face than the one
// written, as the rig files refuse theirs (firmware-host/config/config_node.hpp).
void expect_keys(const Doc& d, const YAML::Node& map,
                 std::initializer_list<std::string_view> keys) {
  if (!map.IsMap()) return;  // the reader of each value says what it expected
  for (const auto& kv : map) {
    const std::string key = kv.first.Scalar();
    if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
    std::string list;
    for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
    throw InputError(d.file, kv.first.Mark().line + 1, kv.first.Mark().column + 1,
                     "expected one of: " + list + ", found unknown key '" + key + "'");
  }
}

YAML::Node need(const Doc& d, const YAML::Node& parent, const std::string& key) {
  YAML::Node n = parent[key];
  if (!n.IsDefined()) {
    int line = parent.Mark().line + 1, col = parent.Mark().column + 1;
    throw InputError(d.file, line, col, "key '" + key + "': expected it here, found nothing");
  }
  return n;
}

template <class T>
T as(const Doc& d, const YAML::Node& n, const std::string& key, const std::string& expected) {
  T v{};
  try {
    if (!n.IsScalar()) fail(d, n, key, expected);
    v = n.as<T>();
  } catch (const YAML::Exception&) {
    fail(d, n, key, expected);
  }
  // yaml-cpp reads .nan and .inf as numbers; no length, stiffness or count of
  // the face model means anything there, and a NaN would blank every render.
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) fail(d, n, key, "a finite number");
  }
  return v;
}

double num(const Doc& d, const YAML::Node& parent, const std::string& key, double fallback) {
  YAML::Node n = parent[key];
  return n.IsDefined() ? as<double>(d, n, key, "a number") : fallback;
}

Vec3 vec_mm(const Doc& d, const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence() || n.size() != 3) fail(d, n, key, "a list of 3 numbers (mm)");
  return Vec3(as<double>(d, n[0], key, "a number"), as<double>(d, n[1], key, "a number"),
              as<double>(d, n[2], key, "a number")) *
         1e-3;
}

std::vector<int> int_list(const Doc& d, const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence() || n.size() == 0) fail(d, n, key, "a non-empty list of vertex indices");
  std::vector<int> out;
  for (const auto& e : n) out.push_back(as<int>(d, e, key, "a vertex index"));
  return out;
}

PointRef point_ref(const Doc& d, const YAML::Node& n, const std::string& key,
                   const std::set<std::string>& names) {
  if (!n.IsMap()) fail(d, n, key, "{ at: LANDMARK, offset_mm: [x, y, z] }");
  expect_keys(d, n, {"at", "offset_mm"});
  PointRef p;
  p.landmark = as<std::string>(d, need(d, n, "at"), "at", "a landmark name");
  if (!names.count(p.landmark)) fail(d, n["at"], "at", "a landmark defined in landmarks.yaml");
  if (n["offset_mm"].IsDefined()) p.offset = vec_mm(d, n["offset_mm"], "offset_mm");
  return p;
}

std::vector<PointRef> refs(const Doc& d, const YAML::Node& n, const std::string& key,
                           std::size_t min_count, const std::set<std::string>& names) {
  if (!n.IsSequence() || n.size() < min_count)
    fail(d, n, key, "a list of at least " + std::to_string(min_count) + " points");
  std::vector<PointRef> out;
  for (const auto& e : n) out.push_back(point_ref(d, e, key, names));
  return out;
}

void read_muscle_stiffness(const Doc& d, const YAML::Node& n, MuscleStiffness& k) {
  if (!n.IsDefined()) return;
  expect_keys(d, n,
              {"up_latitudinal", "up_longitudinal", "low_latitudinal", "low_longitudinal",
               "connection", "up_shear", "low_shear", "bend", "volume", "position"});
  k.up_latitudinal = num(d, n, "up_latitudinal", 0);
  k.up_longitudinal = num(d, n, "up_longitudinal", 0);
  k.low_latitudinal = num(d, n, "low_latitudinal", 0);
  k.low_longitudinal = num(d, n, "low_longitudinal", 0);
  k.connection = num(d, n, "connection", 0);
  k.up_shear = num(d, n, "up_shear", 0);
  k.low_shear = num(d, n, "low_shear", 0);
  k.bend = num(d, n, "bend", 0);
  k.volume = num(d, n, "volume", 0);
  k.position = num(d, n, "position", 0);
}

}  // namespace

double metres_per_unit(const std::string& unit) {
  return unit == "m" ? 1.0 : unit == "cm" ? 0.01 : unit == "mm" ? 0.001 : 0.0;
}

HeadSpec load_head_spec(const std::string& dir) {
  HeadSpec h;
  h.dir = dir;
  Doc face = load(dir + "/face.yaml");
  h.files.push_back("face.yaml");
  YAML::Node f = need(face, face.root, "face");
  expect_keys(face, face.root, {"face"});
  expect_keys(face, f,
              {"skin", "landmarks", "muscles", "openings", "skull", "teeth", "eyelids", "solver",
               "variants", "control_points"});
  YAML::Node skin = need(face, f, "skin");
  expect_keys(face, skin, {"file", "units"});
  h.files.push_back(as<std::string>(face, need(face, skin, "file"), "file", "a file name"));
  h.skin_file = dir + "/" + h.files.back();
  std::string units = as<std::string>(face, need(face, skin, "units"), "units", "m, cm or mm");
  h.skin_scale = metres_per_unit(units);
  if (h.skin_scale == 0) fail(face, skin["units"], "units", "m, cm or mm");
  if (f["openings"].IsDefined()) {
    if (!f["openings"].IsMap()) fail(face, f["openings"], "openings", "a mapping name -> vertices");
    for (const auto& kv : f["openings"])
      h.openings.push_back({kv.first.as<std::string>(), int_list(face, kv.second, "openings")});
  }
  YAML::Node skull = f["skull"];
  expect_keys(face, skull, {"tissue_depth_mm"});
  if (skull.IsDefined()) h.tissue_depth = num(face, skull, "tissue_depth_mm", 8) * 1e-3;
  YAML::Node teeth = f["teeth"];
  expect_keys(face, teeth, {"half_width_mm", "arch_depth_mm", "height_mm", "inset_mm", "gap_mm"});
  if (teeth.IsDefined()) {
    h.teeth_half_width = num(face, teeth, "half_width_mm", 22) * 1e-3;
    h.teeth_depth = num(face, teeth, "arch_depth_mm", 30) * 1e-3;
    h.teeth_height = num(face, teeth, "height_mm", 9) * 1e-3;
    h.teeth_inset = num(face, teeth, "inset_mm", 8) * 1e-3;
    h.teeth_gap = num(face, teeth, "gap_mm", 0.5) * 1e-3;
  }
  YAML::Node lids = f["eyelids"];
  expect_keys(face, lids,
              {"band_mm", "eyeball_radius_mm", "upper_share", "orbicularis_oculi_coupling"});
  if (lids.IsDefined()) {
    h.eyelid_band = num(face, lids, "band_mm", 5) * 1e-3;
    h.eyeball_radius = num(face, lids, "eyeball_radius_mm", 12) * 1e-3;
    h.upper_lid_share = num(face, lids, "upper_share", 0.8);
    h.oculi_lid_coupling = num(face, lids, "orbicularis_oculi_coupling", 0.3);
  }
  YAML::Node solver = f["solver"];
  expect_keys(face, solver,
              {"skin_iterations", "influence_falloff_mm", "skin", "sheet", "sphincter"});
  if (solver.IsDefined()) {
    // Each iteration is a full constraint sweep per frame; 100 is far past the
    // point where more change nothing (docs/FACE_MODEL.md, "Solver").
    const double iterations = num(face, solver, "skin_iterations", 1);
    if (!(iterations >= 1 && iterations <= kMaxSkinIterations &&
          iterations == std::floor(iterations)))
      fail(face, solver["skin_iterations"], "skin_iterations",
           "an integer in 1.." + std::to_string(kMaxSkinIterations));
    h.skin_iterations = static_cast<int>(iterations);
    h.influence_falloff = num(face, solver, "influence_falloff_mm", 25) * 1e-3;
    YAML::Node sk = solver["skin"];
    expect_keys(
        face, sk,
        {"stretch", "bending", "area", "anchor", "volume", "damping", "min_projected_area"});
    if (sk.IsDefined()) {
      h.skin.stretch = num(face, sk, "stretch", h.skin.stretch);
      h.skin.bending = num(face, sk, "bending", h.skin.bending);
      h.skin.area = num(face, sk, "area", h.skin.area);
      h.skin.anchor = num(face, sk, "anchor", h.skin.anchor);
      h.skin.volume = num(face, sk, "volume", h.skin.volume);
      h.skin.damping = num(face, sk, "damping", h.skin.damping);
      h.skin.min_projected_area = num(face, sk, "min_projected_area", h.skin.min_projected_area);
    }
    read_muscle_stiffness(face, solver["sheet"], h.sheet);
    read_muscle_stiffness(face, solver["sphincter"], h.sphincter);
  }
  if (f["variants"].IsDefined()) h.variants = int_list(face, f["variants"], "variants");

  h.files.push_back(as<std::string>(face, need(face, f, "landmarks"), "landmarks", "a file name"));
  Doc lm = load(dir + "/" + h.files.back());
  YAML::Node lms = need(lm, lm.root, "landmarks");
  expect_keys(lm, lm.root, {"landmarks"});
  if (!lms.IsMap())
    fail(lm, lms, "landmarks", "a mapping name -> { vertex | vertices, offset_mm }");
  std::set<std::string> names;
  for (const auto& kv : lms) {
    LandmarkSpec s;
    s.name = kv.first.as<std::string>();
    const YAML::Node& n = kv.second;
    if (!n.IsMap()) fail(lm, n, s.name, "{ vertex: N } or { vertices: [..] }");
    expect_keys(lm, n, {"vertex", "vertices", "offset_mm"});
    const YAML::Node at = n["vertex"].IsDefined() ? n["vertex"] : need(lm, n, "vertices");
    if (n["vertex"].IsDefined())
      s.vertices = {as<int>(lm, at, "vertex", "a vertex index")};
    else
      s.vertices = int_list(lm, at, "vertices");
    s.file = lm.file;
    s.line = at.Mark().line + 1;
    s.column = at.Mark().column + 1;
    if (n["offset_mm"].IsDefined()) s.offset = vec_mm(lm, n["offset_mm"], "offset_mm");
    names.insert(s.name);
    h.landmarks.push_back(s);
  }
  if (f["control_points"].IsDefined()) {
    for (const auto& e : f["control_points"]) {
      std::string n = as<std::string>(face, e, "control_points", "a landmark name");
      if (!names.count(n)) fail(face, e, "control_points", "a landmark defined in landmarks.yaml");
      h.control_points.push_back(n);
    }
  }

  h.files.push_back(as<std::string>(face, need(face, f, "muscles"), "muscles", "a file name"));
  Doc mu = load(dir + "/" + h.files.back());
  YAML::Node ms = need(mu, mu.root, "muscles");
  expect_keys(mu, mu.root, {"muscles"});
  if (!ms.IsSequence()) fail(mu, ms, "muscles", "a list of muscles");
  std::map<std::string, int> first_line;  // a name is its command slot and, for
                                          // orbicularis_oculi_l/_r, the lid it closes
  for (const auto& n : ms) {
    MuscleSpec m;
    expect_keys(
        mu, n,
        {"name", "kind", "layer", "grid", "thickness_mm", "origin", "insertion", "inner", "outer"});
    m.name = as<std::string>(mu, need(mu, n, "name"), "name", "a muscle name");
    const auto [first, fresh] = first_line.emplace(m.name, n["name"].Mark().line + 1);
    if (!fresh)
      fail(mu, n["name"], "name",
           "a name no other muscle has (first at line " + std::to_string(first->second) + ")");
    std::string kind = as<std::string>(mu, need(mu, n, "kind"), "kind", "sheet or sphincter");
    if (kind == "sheet")
      m.kind = MuscleKind::kSheet;
    else if (kind == "sphincter")
      m.kind = MuscleKind::kSphincter;
    else
      fail(mu, n["kind"], "kind", "sheet or sphincter");
    m.layer = as<int>(mu, need(mu, n, "layer"), "layer", "an integer layer (0 = deepest)");
    YAML::Node g = need(mu, n, "grid");
    if (!g.IsSequence() || g.size() != 2) fail(mu, g, "grid", "[rows, cols]");
    m.rows = as<int>(mu, g[0], "grid", "an integer");
    m.cols = as<int>(mu, g[1], "grid", "an integer");
    if (m.rows < 2 || m.cols < 2 || m.rows > kMaxGrid || m.cols > kMaxGrid ||
        (m.kind == MuscleKind::kSphincter && m.rows != 2))
      fail(mu, g, "grid",
           "rows, cols in 2.." + std::to_string(kMaxGrid) + " (a sphincter has rows = 2)");
    m.thickness = as<double>(mu, need(mu, n, "thickness_mm"), "thickness_mm", "a number") * 1e-3;
    if (m.kind == MuscleKind::kSheet) {
      m.origin = refs(mu, need(mu, n, "origin"), "origin", 2, names);
      m.insertion = refs(mu, need(mu, n, "insertion"), "insertion", 2, names);
      if (m.origin.size() != 2 || m.insertion.size() != 2)
        fail(mu, n["origin"], "origin/insertion", "exactly two corner points each");
    } else {
      m.inner = refs(mu, need(mu, n, "inner"), "inner", 3, names);
      m.outer = refs(mu, need(mu, n, "outer"), "outer", 3, names);
    }
    h.muscles.push_back(m);
  }

  Doc hd = load(dir + "/head.yaml");
  YAML::Node head = need(hd, hd.root, "head");
  for (const auto& e : need(hd, head, "muscles"))
    h.commanded.push_back(as<std::string>(hd, need(hd, e, "name"), "name", "a muscle name"));
  for (const auto& e : need(hd, head, "passive_muscles"))
    h.passive.push_back(as<std::string>(hd, e, "passive_muscles", "a muscle name"));
  std::set<std::string> mapped;
  for (const auto& m : h.muscles) mapped.insert(m.name);
  for (const auto& n : h.commanded)
    if (!mapped.count(n))
      throw InputError(mu.file + ": muscle '" + n +
                       "' is commanded by head.yaml but has no geometry");
  for (const auto& n : h.passive)
    if (!mapped.count(n))
      throw InputError(mu.file + ": passive muscle '" + n + "' from head.yaml has no geometry");
  return h;
}

}  // namespace facectl::face
