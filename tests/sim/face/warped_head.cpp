#include "warped_head.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "facectl/face/face_model.hpp"
#include "facectl/face/head_spec.hpp"

namespace facectl::face::testing {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  if (!f) throw std::runtime_error(p.string() + ": cannot read");
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
  if (!f) throw std::runtime_error(p.string() + ": cannot write");
}

Vec3 mm(const YAML::Node& n) {
  return {n[0].as<double>() * 1e-3, n[1].as<double>() * 1e-3, n[2].as<double>() * 1e-3};
}

YAML::Node mm_node(const Vec3& v) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (int k = 0; k < 3; ++k) n.push_back(v[k] * 1e3);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

// Every { at: LANDMARK, offset_mm } below n: the offset carried through the warp.
void warp_refs(YAML::Node n, const std::map<std::string, Vec3>& landmarks) {
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) warp_refs(n[i], landmarks);
  } else if (n.IsMap()) {
    if (n["at"].IsDefined() && n["offset_mm"].IsDefined()) {
      const Vec3 p = landmarks.at(n["at"].as<std::string>());
      n["offset_mm"] = mm_node(warp_head_point(p + mm(n["offset_mm"])) - warp_head_point(p));
      return;
    }
    for (auto kv : n) warp_refs(kv.second, landmarks);
  }
}

std::string emit(const YAML::Node& root) {
  YAML::Emitter out;
  out.SetDoublePrecision(9);
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace

Vec3 warp_head_point(const Vec3& p) {
  // Lower face (below the mouth, y ≤ −4 cm) 15% wider, blending to none above y = +1 cm.
  const double t = std::clamp((0.01 - p.y()) / 0.05, 0.0, 1.0);
  const double lower = t * t * (3 - 2 * t);
  // Cheeks pushed out 3 mm (Gaussian, σ 15 mm, 35 mm either side of the midline).
  auto bump = [&](double cx) {
    const double dx = p.x() - cx, dy = p.y() + 0.015;
    return std::exp(-(dx * dx + dy * dy) / (2 * 0.015 * 0.015));
  };
  return {p.x() * (1 + 0.15 * lower), 0.92 * p.y(), p.z() + 0.003 * (bump(0.035) + bump(-0.035))};
}

void write_warped_head(const std::string& from, const std::string& to) {
  const HeadSpec spec = load_head_spec(from);
  fs::create_directories(to);
  fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  fs::remove(fs::path(to) / "reduced_face.txt");

  // The skin: vertex lines warped in place, everything else kept.
  const double scale = spec.skin_scale;
  std::istringstream obj(read_text(spec.skin_file));
  std::ostringstream warped;
  warped.precision(9);
  for (std::string line; std::getline(obj, line);) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      Vec3 p;
      v >> p.x() >> p.y() >> p.z();
      const Vec3 q = warp_head_point(p * scale) / scale;
      warped << "v " << q.x() << ' ' << q.y() << ' ' << q.z() << '\n';
    } else {
      warped << line << '\n';
    }
  }
  write_text(fs::path(to) / fs::path(spec.skin_file).filename(), warped.str());

  // Landmarks: where each lies on the unwarped skin, and its offset through the warp.
  const Points skin = read_base_skin(spec).v;
  std::map<std::string, Vec3> at;
  for (const LandmarkSpec& l : spec.landmarks) at[l.name] = landmark_position(l, skin);
  const fs::path landmarks_path = spec.landmarks.front().file;
  YAML::Node lms = YAML::LoadFile(landmarks_path.string());
  for (auto kv : lms["landmarks"]) {
    YAML::Node n = kv.second;
    if (!n["offset_mm"].IsDefined()) continue;
    const Vec3 p = at.at(kv.first.as<std::string>());
    const Vec3 on_skin = p - mm(n["offset_mm"]);
    n["offset_mm"] = mm_node(warp_head_point(p) - warp_head_point(on_skin));
  }
  write_text(fs::path(to) / landmarks_path.filename(), emit(lms));

  const fs::path muscles_path = fs::path(from) / "muscles.yaml";
  YAML::Node muscles = YAML::LoadFile(muscles_path.string());
  warp_refs(muscles["muscles"], at);
  write_text(fs::path(to) / "muscles.yaml", emit(muscles));
}

}  // namespace facectl::face::testing
