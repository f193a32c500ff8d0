#include "facectl/face/head_writer.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

namespace fs = std::filesystem;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string mm(double metres) {
  return num(metres * 1e3);
}

std::string vec_mm(const Vec3& v) {
  char buf[96];
  // Values that round to zero print as 0.00, not -0.00.
  auto c = [](double m) { return std::abs(m * 1e3) < 0.005 ? 0.0 : m * 1e3; };
  std::snprintf(buf, sizeof buf, "[%.2f, %.2f, %.2f]", c(v.x()), c(v.y()), c(v.z()));
  return buf;
}

template <class T>
std::string list(const std::vector<T>& xs) {
  std::string s = "[";
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (i) s += ", ";
    if constexpr (std::is_same_v<T, std::string>)
      s += xs[i];
    else
      s += std::to_string(xs[i]);
  }
  return s + "]";
}

std::string stiffness(const MuscleStiffness& k) {
  return "{ up_latitudinal: " + num(k.up_latitudinal) +
         ", up_longitudinal: " + num(k.up_longitudinal) +
         ", low_latitudinal: " + num(k.low_latitudinal) +
         ", low_longitudinal: " + num(k.low_longitudinal) + ", connection: " + num(k.connection) +
         ", up_shear: " + num(k.up_shear) + ", low_shear: " + num(k.low_shear) +
         ", bend: " + num(k.bend) + ", volume: " + num(k.volume) +
         ", position: " + num(k.position) + " }";
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw InputError(path.string() + ": cannot open file for writing");
  out << text;
  if (!out.flush()) throw InputError(path.string() + ": write failed");
}

void copy_into(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (fs::exists(to) && fs::equivalent(from, to, ec)) return;  // --out is the mesh's folder
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) throw InputError(from.string() + ": cannot copy to " + to.string() + ": " + ec.message());
}

std::string face_yaml(const HeadSpec& h, const HeadFolderSources& src) {
  std::ostringstream o;
  o << "# " << src.note << "\n";
  o << "face:\n";
  o << "  skin: { file: skin.obj, units: " << src.skin_units << " }\n";
  o << "  landmarks: landmarks.yaml\n  muscles: muscles.yaml\n";
  o << "  openings:\n";
  for (const auto& [name, verts] : h.openings) o << "    " << name << ": " << list(verts) << "\n";
  o << "  skull: { tissue_depth_mm: " << mm(h.tissue_depth) << " }\n";
  o << "  teeth: { half_width_mm: " << mm(h.teeth_half_width)
    << ", arch_depth_mm: " << mm(h.teeth_depth) << ", height_mm: " << mm(h.teeth_height)
    << ", inset_mm: " << mm(h.teeth_inset) << ", gap_mm: " << mm(h.teeth_gap) << " }\n";
  o << "  eyelids: { band_mm: " << mm(h.eyelid_band)
    << ", eyeball_radius_mm: " << mm(h.eyeball_radius)
    << ", upper_share: " << num(h.upper_lid_share)
    << ", orbicularis_oculi_coupling: " << num(h.oculi_lid_coupling) << " }\n";
  const SkinStiffness& k = h.skin;
  o << "  solver:\n    skin_iterations: " << h.skin_iterations
    << "\n    influence_falloff_mm: " << mm(h.influence_falloff) << "\n";
  o << "    skin: { stretch: " << num(k.stretch) << ", bending: " << num(k.bending)
    << ", area: " << num(k.area) << ", anchor: " << num(k.anchor) << ", volume: " << num(k.volume)
    << ", damping: " << num(k.damping) << ", min_projected_area: " << num(k.min_projected_area)
    << " }\n";
  o << "    sheet: " << stiffness(h.sheet) << "\n";
  o << "    sphincter: " << stiffness(h.sphincter) << "\n";
  if (h.variants.empty())
    o << "  # variants: [vertex counts] (finer skins by edge splitting), none yet\n";
  else
    o << "  variants: " << list(h.variants) << "\n";
  o << "  control_points: " << list(h.control_points) << "\n";
  return o.str();
}

std::string landmarks_yaml(const HeadSpec& h) {
  std::ostringstream o;
  o << "# MPEG-4 feature points on skin.obj (0-based vertex indices), placed by\n"
       "# `facectl face fit-head`; offset_mm moves a bone point off the skin.\n";
  o << "landmarks:\n";
  for (const LandmarkSpec& l : h.landmarks) {
    o << "  " << l.name << ": { ";
    if (l.vertices.size() == 1)
      o << "vertex: " << l.vertices[0];
    else
      o << "vertices: " << list(l.vertices);
    if (l.offset.norm() > 0) o << ", offset_mm: " << vec_mm(l.offset);
    o << " }\n";
  }
  return o.str();
}

void refs(std::ostringstream& o, const char* key, const std::vector<PointRef>& rs) {
  o << "    " << key << ": [";
  for (std::size_t i = 0; i < rs.size(); ++i)
    o << (i ? ", " : "") << "{ at: " << rs[i].landmark << ", offset_mm: " << vec_mm(rs[i].offset)
      << " }";
  o << "]\n";
}

std::string muscles_yaml(const HeadSpec& h) {
  std::ostringstream o;
  o << "# The muscle map carried onto this head by `facectl face fit-head` (RBF morph).\n";
  o << "muscles:\n";
  for (const MuscleSpec& m : h.muscles) {
    const bool sheet = m.kind == MuscleKind::kSheet;
    o << "  - name: " << m.name << "\n    kind: " << (sheet ? "sheet" : "sphincter")
      << "\n    layer: " << m.layer << "\n    grid: [" << m.rows << ", " << m.cols
      << "]\n    thickness_mm: " << mm(m.thickness) << "\n";
    if (sheet) {
      refs(o, "origin", m.origin);
      refs(o, "insertion", m.insertion);
    } else {
      refs(o, "inner", m.inner);
      refs(o, "outer", m.outer);
    }
  }
  return o.str();
}

}  // namespace

void write_head_folder(const std::string& dir, const HeadSpec& spec, const HeadFolderSources& src) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot create folder: " + ec.message());
  const fs::path d(dir);
  copy_into(src.skin_obj, d / "skin.obj");
  write_file(d / "face.yaml", face_yaml(spec, src));
  write_file(d / "landmarks.yaml", landmarks_yaml(spec));
  write_file(d / "muscles.yaml", muscles_yaml(spec));
  copy_into(fs::path(src.source_head) / "head.yaml", d / "head.yaml");
  if (fs::exists(fs::path(src.source_head) / "retarget.yaml"))
    copy_into(fs::path(src.source_head) / "retarget.yaml", d / "retarget.yaml");
  // The mesh's licence travels with it.
  const fs::path obj_dir = fs::absolute(src.skin_obj).parent_path();
  for (const auto& e : fs::directory_iterator(obj_dir, ec)) {
    const std::string n = e.path().filename().string();
    if (e.is_regular_file() && (n.starts_with("NOTICE") || n.starts_with("LICENSE") ||
                                n.starts_with("LICENCE") || n.starts_with("COPYING")))
      copy_into(e.path(), d / n);
  }
}

}  // namespace facectl::face
