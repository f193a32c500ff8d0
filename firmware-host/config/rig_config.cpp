#include "firmware-host/config/rig_config.hpp"

#include <algorithm>
#include <numbers>
#include <set>

#include "control/units.hpp"
#include "firmware-host/config/plant_config.hpp"
#include "firmware-host/config/protection_config.hpp"
#include "firmware-host/model/rig_encoding_check.hpp"

namespace facectl {
namespace {

struct Units {
  std::string suffix;  // "deg" or "mm"
  double to_si;
};

Units units_of(ActuatorKind kind) {
  return {yaml_unit(kind), si_per_yaml(kind)};
}

Range parse_limit_range(const ConfigNode& node, double to_si) {
  node.expect_keys({"min", "max"});
  const double lo = node["min"].number();
  const double hi = node["max"].number();
  if (!(lo < hi))
    node.fail("min < max", "min " + std::to_string(lo) + " >= max " + std::to_string(hi));
  return {lo * to_si, hi * to_si};
}

ActuatorConfig parse_actuator(const ConfigNode& node, const FaceLayout& layout,
                              const std::set<std::string>& bus_names) {
  ActuatorConfig cfg;
  cfg.where = node.where();
  ActuatorModel& m = cfg.model;
  m.name = node["name"].string();
  const std::string kind = node["kind"].string();
  if (kind == "rotary") {
    m.kind = ActuatorKind::kRotary;
  } else if (kind == "linear") {
    m.kind = ActuatorKind::kLinear;
  } else {
    node["kind"].fail("rotary or linear");
  }
  const Units u = units_of(m.kind);
  const std::string s = "_" + u.suffix;
  node.expect_keys({"name", "kind", "bus", "address", "position" + s, "soft_position" + s,
                    "max_velocity" + s + "_s", "max_acceleration" + s + "_s2",
                    "max_jerk" + s + "_s3", "rest" + s, "plant", "map", "fault_reaction",
                    "encoding", "max_current_a", "expect_direction", "protection"});

  m.bus = node["bus"].string();
  if (bus_names.count(m.bus) == 0) node["bus"].fail("the name of a bus of this rig");
  m.address = static_cast<int>(node["address"].integer());

  ActuatorLimits& l = m.limits;
  const Range hard = parse_limit_range(node["position" + s], u.to_si);
  l.position_min = hard.min;
  l.position_max = hard.max;
  Range soft = hard;
  if (auto n = node.get("soft_position" + s)) {
    soft = parse_limit_range(*n, u.to_si);
    if (!hard.contains(soft)) {
      n->fail("a soft range inside position" + s + " [" + std::to_string(hard.min / u.to_si) +
                  ", " + std::to_string(hard.max / u.to_si) + "]",
              "[" + std::to_string(soft.min / u.to_si) + ", " + std::to_string(soft.max / u.to_si) +
                  "]");
    }
  }
  l.soft_min = soft.min;
  l.soft_max = soft.max;
  l.max_velocity = node["max_velocity" + s + "_s"].positive() * u.to_si;
  l.max_acceleration = node["max_acceleration" + s + "_s2"].positive() * u.to_si;
  if (auto n = node.get("max_jerk" + s + "_s3")) l.max_jerk = n->non_negative() * u.to_si;

  const ConfigNode rest = node["rest" + s];
  m.rest = rest.number() * u.to_si;
  if (m.rest < soft.min || m.rest > soft.max) rest.fail("a rest position inside the soft range");

  cfg.plant = parse_plant_config(node.get("plant"), l, u.suffix, u.to_si);
  cfg.plant_where = node.get("plant") ? node["plant"].where() : cfg.where;
  // A strut of the mandible mechanism has no `map`: the mechanism's inverse
  // kinematics drive it (checked when the model is built).
  cfg.has_map = node.has("map");
  if (cfg.has_map) {
    cfg.map = parse_mapping(node["map"], layout, u.suffix);
  } else {
    cfg.map.where = cfg.where;
  }

  cfg.fault_reaction_where = cfg.where;
  if (auto r = node.get("fault_reaction")) {
    cfg.fault_reaction_where = r->where();
    const std::string reaction = r->string();
    if (reaction == "relax") {
      m.fault_reaction = FaultReaction::kRelax;
    } else if (reaction == "hold") {
      m.fault_reaction = FaultReaction::kHold;
    } else if (reaction == "rest") {
      m.fault_reaction = FaultReaction::kRest;
    } else {
      r->fail("one of: relax, hold, rest");
    }
  }
  cfg.encoding_where = cfg.where;
  if (auto e = node.get("encoding")) {
    e->expect_keys({"raw", "scale", "offset"});
    cfg.encoding_where = e->where();
    cfg.has_encoding = true;
    const std::string raw = (*e)["raw"].string();
    if (raw == "int16") {
      m.encoding.raw = ActuatorEncoding::Raw::kInt16;
    } else if (raw == "uint16") {
      m.encoding.raw = ActuatorEncoding::Raw::kUint16;
    } else if (raw == "int32") {
      m.encoding.raw = ActuatorEncoding::Raw::kInt32;
    } else {
      (*e)["raw"].fail("one of: int16, uint16, int32");
    }
    if (auto n = e->get("scale")) {
      m.encoding.scale = n->number();
      if (m.encoding.scale == 0.0) n->fail("a non-zero scale (counts per " + u.suffix + ")");
    }
    if (auto n = e->get("offset")) m.encoding.offset = n->number();
  }
  if (auto c = node.get("max_current_a")) m.max_current_a = c->positive();
  if (auto e = node.get("expect_direction")) {
    for (const auto& [key, value] : e->entries()) {
      const std::size_t index = face_signal(layout, key, value);
      const double sign = value.number();
      if (sign != 1.0 && sign != -1.0) {
        value.fail("+1 (the position rises as the signal rises) or -1 (it falls)");
      }
      cfg.expect_direction.push_back({index, sign > 0 ? 1 : -1, key, value.where()});
    }
  }
  return cfg;
}

CoupledLimitConfig parse_coupled_limit(const ConfigNode& node, const FaceLayout& layout,
                                       const std::vector<ActuatorConfig>& actuators,
                                       const std::optional<MandibleMechanismConfig>& mechanism) {
  node.expect_keys({"name", "face", "actuators", "max"});
  CoupledLimitConfig out;
  out.where = node.where();
  CoupledConstraints::Constraint& c = out.constraint;
  c.name = node["name"].string();
  if (node.has("face") == node.has("actuators")) {
    node.fail("either `face:` (face signals) or `actuators:` (actuator positions)");
  }
  out.over_actuators = node.has("actuators");
  const ConfigNode terms = out.over_actuators ? node["actuators"] : node["face"];
  for (const auto& entry : terms.entries()) {
    // Named, not a structured binding: clang 14 (the sanitizer builds) does
    // not let the lambdas below capture one.
    const std::string& key = entry.first;
    const ConfigNode& coeff = entry.second;
    std::size_t index = 0;
    double to_si = 1.0;
    if (out.over_actuators) {
      auto it = std::find_if(actuators.begin(), actuators.end(),
                             [&](const ActuatorConfig& a) { return a.model.name == key; });
      if (it == actuators.end()) coeff.fail("the name of an actuator of this rig", "'" + key + "'");
      // A strut follows the jaw's pose, not its own limiter, so its bound
      // could not be kept exactly (docs/SAFETY.md, actuator coupled limits).
      if (mechanism && std::any_of(mechanism->struts.begin(), mechanism->struts.end(),
                                   [&](const StrutConfig& s) { return s.actuator == key; })) {
        coeff.fail(
            "an actuator that is not a strut of the mandible mechanism (struts follow the "
            "jaw's pose: bound the jaw with a face coupled limit over jaw_pitch_deg, "
            "jaw_yaw_deg and jaw_protrusion_mm instead)",
            "strut '" + key + "'");
      }
      index = static_cast<std::size_t>(it - actuators.begin());
      to_si = units_of(it->model.kind).to_si;
    } else {
      const auto found = layout.find_yaml_key(key);
      if (!found) coeff.fail("a face signal of the head (with its unit suffix)", "'" + key + "'");
      index = *found;
      to_si = yaml_to_si(layout.signal(index).kind);
    }
    if (c.terms == CoupledConstraints::kMaxTerms) {
      coeff.fail("at most " + std::to_string(CoupledConstraints::kMaxTerms) + " terms");
    }
    c.index[c.terms] = index;
    // Coefficient per YAML unit -> per SI unit, so the bound keeps its YAML meaning.
    c.coeff[c.terms] = coeff.number() / to_si;
    ++c.terms;
  }
  if (c.terms == 0) terms.fail("at least one term", "an empty mapping");
  c.bound = node["max"].number();
  return out;
}

// A strut follows the jaw's pose by inverse kinematics, not its own target,
// so its command cannot be derated or kept out of a band on its own.
void refuse_strut_derating(const RigConfig& cfg) {
  for (const StrutConfig& s : cfg.mechanism->struts) {
    for (const ActuatorConfig& a : cfg.actuators) {
      const DriveProtection& p = a.protection;
      if (a.model.name != s.actuator || !p.configured) continue;
      const bool derates = p.temperature_c.derate < p.temperature_c.fault ||
                           p.load.derate < p.load.fault || p.current_a.derate < p.current_a.fault ||
                           p.extreme_band > 0.0;
      if (derates) {
        throw ConfigError(a.protection_where + ": rig.actuators '" + a.model.name +
                          "'.protection: expected fault thresholds only on a strut of the "
                          "mandible mechanism (it follows the jaw's pose: no derate, no "
                          "extreme band), found a derate threshold or an extreme band");
      }
    }
  }
}

}  // namespace

RigConfig load_rig_config(const std::string& path, const FaceLayout& layout) {
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"rig"});
  const ConfigNode rig = root["rig"];
  rig.expect_keys(
      {"name", "buses", "actuators", "mandible_envelope", "mandible_mechanism", "coupled_limits"});

  RigConfig cfg;
  cfg.file = path;
  cfg.name = rig["name"].string();
  std::set<std::string> bus_names;
  for (const ConfigNode& b : rig["buses"].items()) {
    BusConfig bus = parse_bus_config(b);
    if (!bus_names.insert(bus.name).second) b["name"].fail("a unique bus name");
    cfg.buses.push_back(std::move(bus));
  }
  if (cfg.buses.empty()) rig["buses"].fail("at least one bus", "an empty list");
  if (cfg.buses.size() > kMaxBuses)
    rig["buses"].fail("at most " + std::to_string(kMaxBuses) + " buses");

  std::set<std::string> names;
  std::set<std::pair<std::string, int>> addresses;
  const auto items = rig["actuators"].items();
  if (items.empty()) rig["actuators"].fail("at least one actuator", "an empty list");
  if (items.size() > kMaxActuators) {
    rig["actuators"].fail("at most " + std::to_string(kMaxActuators) + " actuators");
  }
  for (const ConfigNode& a : items) {
    ActuatorConfig act = parse_actuator(a, layout, bus_names);
    if (!names.insert(act.model.name).second) a["name"].fail("a unique actuator name");
    if (!addresses.insert({act.model.bus, act.model.address}).second) {
      a["address"].fail("an address not used by another actuator on bus " + act.model.bus);
    }
    const auto bus = std::find_if(cfg.buses.begin(), cfg.buses.end(),
                                  [&](const BusConfig& b) { return b.name == act.model.bus; });
    check_actuator_encoding(act, *bus);
    if (auto p = a.get("protection")) {
      act.protection = parse_protection(*p, act.model, *bus);
      act.protection_where = p->where();
    }
    if (bus->is_cia402() && act.model.address == bus->can.host_node) {
      a["address"].fail("a node id other than the host's (host_node " +
                        std::to_string(bus->can.host_node) + " on bus " + bus->name + ")");
    }
    cfg.actuators.push_back(std::move(act));
  }
  if (auto env = rig.get("mandible_envelope")) cfg.envelope = parse_envelope(*env);
  if (auto mech = rig.get("mandible_mechanism")) cfg.mechanism = parse_mandible_mechanism(*mech);
  if (cfg.mechanism) refuse_strut_derating(cfg);
  if (auto limits = rig.get("coupled_limits")) {
    const auto rows = limits->items();
    if (rows.size() > CoupledConstraints::kMaxConstraints) {
      limits->fail("at most " + std::to_string(CoupledConstraints::kMaxConstraints) +
                   " coupled limits");
    }
    for (const ConfigNode& c : rows) {
      cfg.coupled_limits.push_back(parse_coupled_limit(c, layout, cfg.actuators, cfg.mechanism));
    }
  }
  return cfg;
}

}  // namespace facectl
