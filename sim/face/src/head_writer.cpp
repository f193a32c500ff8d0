#include "facectl/face/head_writer.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <system_error>

#include "facectl/face/input_error.hpp"
#include "facectl/face/yaml_emit.hpp"

namespace facectl::face {
namespace {

namespace fs = std::filesystem;

using Y = YAML::Emitter;

// Lengths are written in mm, as the readers take them.
YamlScaled mm(double metres) {
  return {metres, 1e-3};
}

void vec_mm(Y& y, const Vec3& v) {
  y << YAML::Flow << YAML::BeginSeq << mm(v.x()) << mm(v.y()) << mm(v.z()) << YAML::EndSeq;
}

void ints(Y& y, const std::vector<int>& xs) {
  y << YAML::Flow << YAML::BeginSeq;
  for (const int x : xs) y << x;
  y << YAML::EndSeq;
}

void names(Y& y, const std::vector<std::string>& xs) {
  y << YAML::Flow << YAML::BeginSeq;
  for (const std::string& x : xs) y << YamlName{x};
  y << YAML::EndSeq;
}

// A value and what the reader multiplies the file's number by (1e-3 for a length in mm).
struct Num {
  const char* key;
  double si, si_per_unit = 1;
};

// `key: {a: 1, b: 2}`, a table of numbers on one line.
void numbers(Y& y, const char* key, std::initializer_list<Num> ns) {
  y << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const Num& n : ns) y << YAML::Key << n.key << YAML::Value << YamlScaled{n.si, n.si_per_unit};
  y << YAML::EndMap;
}

void stiffness(Y& y, const char* key, const MuscleStiffness& k) {
  numbers(y, key,
          {{"up_latitudinal", k.up_latitudinal},
           {"up_longitudinal", k.up_longitudinal},
           {"low_latitudinal", k.low_latitudinal},
           {"low_longitudinal", k.low_longitudinal},
           {"connection", k.connection},
           {"up_shear", k.up_shear},
           {"low_shear", k.low_shear},
           {"bend", k.bend},
           {"volume", k.volume},
           {"position", k.position}});
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
  Y y;
  y << YAML::Comment(src.note) << YAML::Newline << YAML::BeginMap;
  y << YAML::Key << "face" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "skin" << YAML::Value << YAML::Flow << YAML::BeginMap;
  y << YAML::Key << "file" << YAML::Value << "skin.obj";
  y << YAML::Key << "units" << YAML::Value << YamlName{src.skin_units} << YAML::EndMap;
  y << YAML::Key << "landmarks" << YAML::Value << "landmarks.yaml";
  y << YAML::Key << "muscles" << YAML::Value << "muscles.yaml";
  y << YAML::Key << "openings" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, verts] : h.openings) {
    y << YAML::Key << YamlName{name} << YAML::Value;
    ints(y, verts);
  }
  y << YAML::EndMap;
  constexpr double kMm = 1e-3;
  numbers(y, "skull", {{"tissue_depth_mm", h.tissue_depth, kMm}});
  numbers(y, "teeth",
          {{"half_width_mm", h.teeth_half_width, kMm},
           {"arch_depth_mm", h.teeth_depth, kMm},
           {"height_mm", h.teeth_height, kMm},
           {"inset_mm", h.teeth_inset, kMm},
           {"gap_mm", h.teeth_gap, kMm}});
  numbers(y, "eyelids",
          {{"band_mm", h.eyelid_band, kMm},
           {"eyeball_radius_mm", h.eyeball_radius, kMm},
           {"upper_share", h.upper_lid_share},
           {"orbicularis_oculi_coupling", h.oculi_lid_coupling}});
  const SkinStiffness& k = h.skin;
  y << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "skin_iterations" << YAML::Value << h.skin_iterations;
  y << YAML::Key << "influence_falloff_mm" << YAML::Value << mm(h.influence_falloff);
  numbers(y, "skin",
          {{"stretch", k.stretch},
           {"bending", k.bending},
           {"area", k.area},
           {"anchor", k.anchor},
           {"volume", k.volume},
           {"damping", k.damping},
           {"min_projected_area", k.min_projected_area}});
  stiffness(y, "sheet", h.sheet);
  stiffness(y, "sphincter", h.sphincter);
  y << YAML::EndMap;
  if (h.variants.empty()) {
    y << YAML::Newline
      << YAML::Comment("variants: [vertex counts] (finer skins by edge splitting), none yet");
  } else {
    y << YAML::Key << "variants" << YAML::Value;
    ints(y, h.variants);
  }
  y << YAML::Key << "control_points" << YAML::Value;
  names(y, h.control_points);
  y << YAML::EndMap << YAML::EndMap;
  return emitted(y);
}

std::string landmarks_yaml(const HeadSpec& h) {
  Y y;
  y << YAML::Comment(
           "MPEG-4 feature points on skin.obj (0-based vertex indices), placed by\n"
           "`facectl face fit-head`; offset_mm moves a bone point off the skin.")
    << YAML::Newline << YAML::BeginMap << YAML::Key << "landmarks" << YAML::Value << YAML::BeginMap;
  for (const LandmarkSpec& l : h.landmarks) {
    y << YAML::Key << YamlName{l.name} << YAML::Value << YAML::Flow << YAML::BeginMap;
    if (l.vertices.size() == 1) {
      y << YAML::Key << "vertex" << YAML::Value << l.vertices[0];
    } else {
      y << YAML::Key << "vertices" << YAML::Value;
      ints(y, l.vertices);
    }
    if (l.offset.norm() > 0) {
      y << YAML::Key << "offset_mm" << YAML::Value;
      vec_mm(y, l.offset);
    }
    y << YAML::EndMap;
  }
  y << YAML::EndMap << YAML::EndMap;
  return emitted(y);
}

void refs(Y& y, const char* key, const std::vector<PointRef>& rs) {
  y << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const PointRef& r : rs) {
    y << YAML::BeginMap << YAML::Key << "at" << YAML::Value << YamlName{r.landmark};
    y << YAML::Key << "offset_mm" << YAML::Value;
    vec_mm(y, r.offset);
    y << YAML::EndMap;
  }
  y << YAML::EndSeq;
}

std::string muscles_yaml(const HeadSpec& h) {
  Y y;
  y << YAML::Comment(
           "The muscle map carried onto this head by `facectl face fit-head` (RBF morph).")
    << YAML::Newline << YAML::BeginMap << YAML::Key << "muscles" << YAML::Value << YAML::BeginSeq;
  for (const MuscleSpec& m : h.muscles) {
    const bool sheet = m.kind == MuscleKind::kSheet;
    y << YAML::BeginMap << YAML::Key << "name" << YAML::Value << YamlName{m.name};
    y << YAML::Key << "kind" << YAML::Value << (sheet ? "sheet" : "sphincter");
    y << YAML::Key << "layer" << YAML::Value << m.layer;
    y << YAML::Key << "grid" << YAML::Value;
    ints(y, {m.rows, m.cols});
    y << YAML::Key << "thickness_mm" << YAML::Value << mm(m.thickness);
    if (sheet) {
      refs(y, "origin", m.origin);
      refs(y, "insertion", m.insertion);
    } else {
      refs(y, "inner", m.inner);
      refs(y, "outer", m.outer);
    }
    y << YAML::EndMap;
  }
  y << YAML::EndSeq << YAML::EndMap;
  return emitted(y);
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
