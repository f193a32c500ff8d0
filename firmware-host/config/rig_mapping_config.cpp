#include "firmware-host/config/rig_mapping_config.hpp"

#include <cmath>
#include <numbers>

#include "control/units.hpp"

namespace facectl {
namespace {

std::string suffixed(const std::string& key, const std::string& unit) {
  return unit.empty() ? key : key + "_" + unit;
}

// The effector unit of each linkage: lever pulls a cable, the others turn a rocker or crank.
std::string linkage_effector_unit(Linkage::Kind kind) {
  return kind == Linkage::Kind::kLever ? "mm" : "deg";
}

Linkage parse_linkage(const ConfigNode& node) {
  Linkage l;
  const std::string kind = node["kind"].string();
  if (kind == "lever") {
    node.expect_keys({"kind", "radius_mm"});
    l.kind = Linkage::Kind::kLever;
    l.radius = node["radius_mm"].positive() * 1e-3;
    return l;
  }
  if (kind == "four_bar") {
    node.expect_keys({"kind", "ground_mm", "input_mm", "coupler_mm", "output_mm", "branch",
                      "phase_deg", "effector_deg"});
    l.kind = Linkage::Kind::kFourBar;
    l.ground = node["ground_mm"].positive() * 1e-3;
    l.input = node["input_mm"].positive() * 1e-3;
    l.coupler = node["coupler_mm"].positive() * 1e-3;
    l.output = node["output_mm"].positive() * 1e-3;
    if (auto b = node.get("branch")) {
      l.branch = static_cast<int>(b->integer());
      if (l.branch != 1 && l.branch != -1) b->fail("+1 or -1");
    }
  } else if (kind == "slider_crank") {
    node.expect_keys({"kind", "crank_mm", "rod_mm", "offset_mm", "phase_deg", "effector_deg"});
    l.kind = Linkage::Kind::kSliderCrank;
    l.input = node["crank_mm"].positive() * 1e-3;
    l.coupler = node["rod_mm"].positive() * 1e-3;
    if (auto o = node.get("offset_mm")) l.offset = o->number() * 1e-3;
  } else {
    node["kind"].fail("one of: lever, four_bar, slider_crank");
  }
  if (auto p = node.get("phase_deg")) l.phase = p->number() * kDeg;
  const ConfigNode range = node["effector_deg"];
  range.expect_keys({"min", "max"});
  l.effector_min = range["min"].number() * kDeg;
  l.effector_max = range["max"].number() * kDeg;
  if (!(l.effector_min < l.effector_max)) range.fail("min < max");
  return l;
}

// `calibration: { effector_<unit>: [...], position_<unit>: [...] }`.
CalibrationCurve parse_calibration(const ConfigNode& node, const std::string& actuator_unit,
                                   std::string* effector_unit, std::string* problem) {
  std::string x_key;
  for (const auto& [key, value] : node.entries()) {
    if (key.rfind("effector", 0) == 0) x_key = key;
  }
  if (x_key.empty()) node.fail("an effector list (effector_mm, effector_deg or effector)");
  *effector_unit = x_key == "effector" ? "" : x_key.substr(std::string("effector_").size());
  if (*effector_unit != "" && *effector_unit != "mm" && *effector_unit != "deg") {
    node[x_key].fail("effector_mm, effector_deg or effector (dimensionless)");
  }
  const std::string y_key = "position_" + actuator_unit;
  node.expect_keys({x_key, y_key});
  const auto xs = node[x_key].items();
  const auto ys = node[y_key].items();
  if (xs.size() != ys.size()) {
    node[y_key].fail(std::to_string(xs.size()) + " values, one per " + x_key + " value",
                     std::to_string(ys.size()) + " values");
  }
  if (xs.size() < 2 || xs.size() > CalibrationCurve::kMaxPoints) {
    node[x_key].fail("2.." + std::to_string(CalibrationCurve::kMaxPoints) + " points",
                     std::to_string(xs.size()));
  }
  std::vector<double> x, y;
  for (const auto& n : xs) x.push_back(n.number() * unit_to_si(*effector_unit));
  for (const auto& n : ys) y.push_back(n.number() * unit_to_si(actuator_unit));
  for (std::size_t k = 1; k < x.size(); ++k) {
    if (!(x[k] > x[k - 1])) xs[k].fail("strictly increasing " + x_key, xs[k].found());
  }
  // A curve that turns back is not invertible and cannot be run, but it is a
  // finding about the rig (facectl verify names it), not an unreadable file.
  const bool up = y.back() > y.front();
  for (std::size_t k = 1; k < y.size(); ++k) {
    if ((y[k] > y[k - 1]) != up || y[k] == y[k - 1]) {
      *problem = ys[k].where() + ": calibration is not monotone: " + x_key + " " +
                 xs[k - 1].found() + " -> " + y_key + " " + ys[k - 1].found() + ", but " + x_key +
                 " " + xs[k].found() + " -> " + y_key + " " + ys[k].found();
      return {};
    }
  }
  CalibrationCurve curve;
  curve.set(x.data(), y.data(), x.size());
  return curve;
}

}  // namespace

double unit_to_si(const std::string& unit) {
  if (unit == "deg") return kDeg;
  if (unit == "mm") return 1e-3;
  return 1.0;
}

std::size_t face_signal(const FaceLayout& layout, const std::string& key, const ConfigNode& at) {
  // A face signal is named with its YAML unit: zygomaticus_major_l, jaw_pitch_deg, ...
  const std::optional<std::size_t> index = layout.find_yaml_key(key);
  if (!index) {
    at.fail("a face signal of the head (muscle name, jaw_pitch_deg, jaw_protrusion_mm, ...)",
            "unknown signal '" + key + "'");
  }
  return *index;
}

MappingConfig parse_mapping(const ConfigNode& map, const FaceLayout& layout,
                            const std::string& actuator_unit) {
  MappingConfig cfg;
  cfg.where = map.where();
  cfg.effector_unit = actuator_unit;
  if (map.has("calibration") && map.has("linkage")) {
    map["linkage"].fail("one transform: calibration or linkage, not both");
  }
  if (auto c = map.get("calibration")) {
    cfg.transform.kind = ChannelTransform::Kind::kCalibration;
    cfg.transform.curve =
        parse_calibration(*c, actuator_unit, &cfg.effector_unit, &cfg.calibration_problem);
    cfg.transform_where = c->where();
  } else if (auto l = map.get("linkage")) {
    cfg.transform.kind = ChannelTransform::Kind::kLinkage;
    cfg.transform.linkage = parse_linkage(*l);
    cfg.effector_unit = linkage_effector_unit(cfg.transform.linkage.kind);
    cfg.transform_where = l->where();
  }
  const std::string offset_key = suffixed("offset", cfg.effector_unit);
  map.expect_keys({offset_key, "terms", "points", "calibration", "linkage"});
  const double to_si = unit_to_si(cfg.effector_unit);
  if (auto n = map.get(offset_key)) cfg.offset_si = n->number() * to_si;
  if (auto terms = map.get("terms")) {
    for (const auto& [signal_key, gain] : terms->entries()) {
      const std::size_t index = face_signal(layout, signal_key, gain);
      // Gain is in effector YAML units per signal YAML unit.
      cfg.terms.push_back({index, gain.number() * to_si / yaml_to_si(layout.signal(index).kind)});
    }
  }
  if (auto points = map.get("points")) {
    for (const ConfigNode& p : points->items()) {
      p.expect_keys({"point", "axis", "gain"});
      PointTermConfig t;
      t.where = p.where();
      t.point = p["point"].string();
      const auto axis = p["axis"].items();
      if (axis.size() != 3) p["axis"].fail("3 numbers [x, y, z] (head frame)");
      double norm = 0.0;
      for (std::size_t k = 0; k < 3; ++k) {
        t.axis[k] = axis[k].number();
        norm += t.axis[k] * t.axis[k];
      }
      if (norm <= 0.0) p["axis"].fail("a non-zero direction", "[0, 0, 0]");
      for (double& a : t.axis) a /= std::sqrt(norm);
      // Gain: effector YAML units per millimetre of displacement along the axis.
      t.gain_si = p["gain"].number() * to_si / 1e-3;
      cfg.points.push_back(t);
    }
  }
  return cfg;
}

}  // namespace facectl
