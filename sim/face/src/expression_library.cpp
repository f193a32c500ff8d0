#include "facectl/face/expression_library.hpp"

#include <yaml-cpp/yaml.h>

#include <numbers>

#include "control/envelope/mandible_envelope.hpp"
#include "control/units.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/yaml_file.hpp"

namespace facectl::face {
namespace {

[[noreturn]] void bad(const std::string& file, const YAML::Node& n, const std::string& what) {
  throw InputError(file, n.Mark().line + 1, n.Mark().column + 1, what);
}

double number(const std::string& file, const YAML::Node& n, const std::string& key) {
  try {
    if (!n.IsScalar())
      bad(file, n,
          "key '" + key + "': expected a number, found a " + (n.IsMap() ? "mapping" : "list"));
    return n.as<double>();
  } catch (const YAML::Exception&) {
    bad(file, n, "key '" + key + "': expected a number, found '" + n.Scalar() + "'");
  }
}

}  // namespace

const Expression* ExpressionLibrary::find(const std::string& name) const {
  for (const Expression& e : expressions)
    if (e.name == name) return &e;
  return nullptr;
}

ExpressionLibrary load_expression_library(const std::string& path, const HeadSpec& head) {
  const YAML::Node root = load_yaml_file(path);
  ExpressionLibrary lib;
  const YAML::Node ex = root["expressions"];
  if (!ex.IsMap())
    throw InputError(path + ": key 'expressions': expected a mapping of expressions");
  for (const auto& kv : ex) {
    Expression e;
    e.name = kv.first.as<std::string>();
    e.contractions.assign(head.commanded.size(), 0.0);
    const YAML::Node& n = kv.second;
    if (!n.IsMap()) bad(path, n, "expression '" + e.name + "': expected a mapping");
    for (const auto& item : n) {
      const std::string key = item.first.as<std::string>();
      if (key != "muscles" && key != "mandible" && key != "rigid")
        bad(path, item.first, "key '" + key + "': expected muscles, mandible or rigid");
    }
    if (n["muscles"].IsDefined()) {
      for (const auto& m : n["muscles"]) {
        const std::string name = m.first.as<std::string>();
        std::size_t slot = 0;
        while (slot < head.commanded.size() && head.commanded[slot] != name) ++slot;
        if (slot == head.commanded.size())
          bad(path, m.first, "muscle '" + name + "': expected a commanded muscle of head.yaml");
        const double c = number(path, m.second, name);
        if (c < 0 || c > 1)
          bad(path, m.second, "muscle '" + name + "': expected 0..1, found " + m.second.Scalar());
        e.contractions[slot] = c;
      }
    }
    if (n["mandible"].IsDefined()) {
      const YAML::Node j = n["mandible"];
      auto get = [&](const char* key, double lo, double hi) {
        if (!j[key].IsDefined()) return 0.0;
        const double v = number(path, j[key], key);
        if (v < lo || v > hi)
          bad(path, j[key],
              std::string("key '") + key + "': expected " + std::to_string(lo) + ".." +
                  std::to_string(hi) + ", found " + j[key].Scalar());
        return v;
      };
      e.jaw.pitch_rad = get("pitch_deg", kJawPitchMinDeg, kJawPitchMaxDeg) * kDeg;
      e.jaw.yaw_rad = get("yaw_deg", -kJawYawMaxDeg, kJawYawMaxDeg) * kDeg;
      e.jaw.protrusion_m = get("protrusion_mm", 0, kJawProtrusionMaxMm) * 1e-3;
    }
    if (n["rigid"].IsDefined()) {
      for (const auto& r : n["rigid"]) {
        const std::string key = r.first.as<std::string>();
        const double v = number(path, r.second, key);
        if (v < 0 || v > 1) bad(path, r.second, "key '" + key + "': expected 0..1");
        if (key == "eyelid_closure_l")
          e.eyelid_closure[0] = v;
        else if (key == "eyelid_closure_r")
          e.eyelid_closure[1] = v;
        else if (key == "eyelid_closure")
          e.eyelid_closure[0] = e.eyelid_closure[1] = v;
        else
          bad(path, r.first,
              "key '" + key + "': expected eyelid_closure, eyelid_closure_l or eyelid_closure_r");
      }
    }
    lib.expressions.push_back(std::move(e));
  }
  const YAML::Node seq = root["sequences"];
  if (seq.IsDefined()) {
    for (const auto& kv : seq) {
      PoseSequence s;
      s.name = kv.first.as<std::string>();
      s.period_s = number(path, kv.second["period_s"], "period_s");
      for (const auto& p : kv.second["poses"]) {
        const std::string name = p.as<std::string>();
        if (!lib.find(name))
          bad(path, p, "pose '" + name + "': expected an expression of this file");
        s.poses.push_back(name);
      }
      lib.sequences.push_back(std::move(s));
    }
  }
  return lib;
}

FaceInput face_input(const Expression& e) {
  FaceInput in;
  in.contractions = e.contractions;
  in.jaw = e.jaw;
  in.eyelid_closure[0] = e.eyelid_closure[0];
  in.eyelid_closure[1] = e.eyelid_closure[1];
  return in;
}

void simulate_expression(const FaceModel& m, FaceData& d, const Expression& e, int frames) {
  reset_face_data(m, d);
  const FaceInput in = face_input(e);
  for (int f = 0; f < frames; ++f) step_face(m, d, in);
}

}  // namespace facectl::face
