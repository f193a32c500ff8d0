#include "tests/support/mandible_mechanisms.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "facectl/face/face_model.hpp"
#include "facectl/face/head_spec.hpp"

namespace facectl::testing {
namespace {

// The ```yaml blocks of the page that hold a `mandible_mechanism` key.
std::vector<YAML::Node> documented_mechanisms() {
  std::ifstream in(std::string(FACECTL_SOURCE_DIR) + "/docs/MANDIBLE_MECHANISM.md");
  if (!in) throw std::runtime_error("cannot read docs/MANDIBLE_MECHANISM.md");
  std::vector<YAML::Node> out;
  std::string line, block;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line.rfind("```yaml", 0) == 0) {
      inside = true;
      block.clear();
    } else if (inside && line.rfind("```", 0) == 0) {
      inside = false;
      const YAML::Node node = YAML::Load(block);
      if (node["mandible_mechanism"]) out.push_back(node["mandible_mechanism"]);
    } else if (inside) {
      block += line + "\n";
    }
  }
  return out;
}

Eigen::Vector3d millimetres(const YAML::Node& n) {
  return Eigen::Vector3d(n[0].as<double>(), n[1].as<double>(), n[2].as<double>()) * 1e-3;
}

}  // namespace

const face::MandibleAxes& default_head_axes() {
  static const face::MandibleAxes axes =
      face::build_face_model(face::load_head_spec(FACECTL_DEFAULT_HEAD_DIR)).axes;
  return axes;
}

MandibleMechanism proposed_mechanism(std::size_t struts) {
  // Soft limits suggested on the page for the actuators it names, mm.
  const std::map<std::string, Range> limits = {{"jaw_digastric", {2, 48}},
                                               {"jaw_digastric_l", {2, 48}},
                                               {"jaw_digastric_r", {2, 48}},
                                               {"jaw_pterygoid_l", {1, 29}},
                                               {"jaw_pterygoid_r", {1, 29}}};
  for (const YAML::Node& mech : documented_mechanisms()) {
    if (mech["struts"].size() != struts) continue;
    std::vector<MandibleDof> dofs;
    for (const YAML::Node& d : mech["dofs"]) {
      const std::string name = d.as<std::string>();
      dofs.push_back(name == "pitch" ? MandibleDof::kPitch
                     : name == "yaw" ? MandibleDof::kYaw
                                     : MandibleDof::kProtrusion);
    }
    std::vector<MandibleStrut> list;
    for (const YAML::Node& s : mech["struts"]) {
      MandibleStrut strut;
      strut.actuator = list.size();
      strut.skull = millimetres(s["skull_mm"]);
      strut.mandible = millimetres(s["mandible_mm"]);
      strut.stroke_at_rest = s["stroke_at_rest_mm"].as<double>() * 1e-3;
      const Range r = limits.at(s["actuator"].as<std::string>());
      strut.stroke = {r.min * 1e-3, r.max * 1e-3};
      list.push_back(strut);
    }
    return make_mandible_mechanism(default_head_axes(), dofs, list,
                                   MandibleEnvelope::design_default());
  }
  throw std::runtime_error("docs/MANDIBLE_MECHANISM.md has no mechanism with " +
                           std::to_string(struts) + " struts");
}

}  // namespace facectl::testing
