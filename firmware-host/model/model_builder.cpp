#include "firmware-host/model/model_builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "control/units.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/model/mechanism_builder.hpp"

namespace facectl {
namespace {

Range intersect(const Range& a, const Range& b) {
  return {std::max(a.min, b.min), std::min(a.max, b.max)};
}

std::string describe(const MandibleEnvelope& e) {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "pitch %.2f..%.2f deg, yaw %.2f..%.2f deg, protrusion %.2f..%.2f mm",
                e.pitch.min / kDeg, e.pitch.max / kDeg, e.yaw.min / kDeg, e.yaw.max / kDeg,
                e.protrusion.min * 1e3, e.protrusion.max * 1e3);
  return buf;
}

// A rig axis wider than what it would narrow, stated without the override, is
// silently narrowed at run time: the rig's author meant something else.
void check_unmarked_widening(const EnvelopeSpec& spec, const MandibleEnvelope& before,
                             std::vector<std::string>& problems) {
  if (spec.widen_override) return;
  auto check = [&](const std::optional<Range>& stated, const Range& axis, const char* name,
                   double unit, const char* suffix) {
    if (stated && !axis.contains(*stated)) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "%s: mandible_envelope.%s: states %.2f..%.2f %s, wider than the %.2f..%.2f %s "
                    "it narrows, without `widen_override: true`",
                    spec.where.c_str(), name, stated->min / unit, stated->max / unit, suffix,
                    axis.min / unit, axis.max / unit, suffix);
      problems.emplace_back(buf);
    }
  };
  check(spec.pitch, before.pitch, "pitch_deg", kDeg, "deg");
  check(spec.yaw, before.yaw, "yaw_deg", kDeg, "deg");
  check(spec.protrusion, before.protrusion, "protrusion_mm", 1e-3, "mm");
}

// The card's joint limits are the product's hard limit: `widen_override` may
// undo a head's narrowing, never go beyond them. `facectl run` refuses such a
// rig; `facectl verify` fails it.
void check_within_joint_limits(const HeadConfig& head, const RigConfig& rig,
                               const MandibleEnvelope& env, const MandibleEnvelope& design,
                               std::vector<std::string>& problems) {
  auto check = [&](const Range& axis, const Range& limit,
                   std::optional<Range> EnvelopeSpec::*stated, const char* name, double unit,
                   const char* suffix) {
    if (limit.contains(axis)) return;
    // The last block that widened this axis.
    const bool by_rig =
        rig.envelope && rig.envelope->widen_override && ((*rig.envelope).*stated).has_value();
    const std::string where = by_rig          ? rig.envelope->where
                              : head.envelope ? head.envelope->where
                                              : rig.file;
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "%s: mandible_envelope.%s: %g..%g %s, beyond the mandible's joint limits "
                  "%g..%g %s (the product's hard limit: `widen_override` cannot exceed them)",
                  where.c_str(), name, axis.min / unit, axis.max / unit, suffix, limit.min / unit,
                  limit.max / unit, suffix);
    problems.emplace_back(buf);
  };
  check(env.pitch, design.pitch, &EnvelopeSpec::pitch, "pitch_deg", kDeg, "deg");
  check(env.yaw, design.yaw, &EnvelopeSpec::yaw, "yaw_deg", kDeg, "deg");
  check(env.protrusion, design.protrusion, &EnvelopeSpec::protrusion, "protrusion_mm", 1e-3, "mm");
}

// The reduced face model of the head, for rigs that read control points.
std::shared_ptr<const face::ReducedFaceModel> load_reduced(const HeadConfig& head) {
  const std::string dir = head.file.substr(0, head.file.find_last_of('/') + 1);
  try {
    const face::HeadSpec spec = face::load_head_spec(dir.empty() ? "." : dir);
    return std::make_shared<const face::ReducedFaceModel>(
        face::load_reduced_model(dir + "reduced_face.txt", spec));
  } catch (const face::InputError& e) {
    throw ConfigError(std::string(e.what()) + " (the rig reads control points of this head)");
  }
}

// The face signals: layout, neutral pose and admissible ranges from the head.
void set_face_signals(const HeadConfig& head, ControllerModel& m) {
  m.layout = head.layout;
  m.neutral = head.neutral;
  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    const SignalInfo& info = m.layout.signal(i);
    m.admissible[i] = {info.domain_min, info.domain_max};
    if (auto it = head.rigid_ranges.find(info.name); it != head.rigid_ranges.end()) {
      m.admissible[i] = it->second;
    }
  }
}

// Envelope, axis by axis: the design default, then the head's, then the
// rig's. A stated axis narrows (intersects) unless its block carries
// `widen_override`, in which case it replaces. Anything wider than the
// design default, or than the head's own envelope, is announced loudly.
void set_envelope(const HeadConfig& head, const RigConfig& rig, BuiltModel& out) {
  ControllerModel& m = out.model;
  const MandibleEnvelope design = MandibleEnvelope::design_default();
  auto apply = [](Range& axis, const std::optional<Range>& stated, bool override_widen) {
    if (stated) axis = override_widen ? *stated : intersect(axis, *stated);
  };
  MandibleEnvelope env = design;
  if (head.envelope) {
    apply(env.pitch, head.envelope->pitch, head.envelope->widen_override);
    apply(env.yaw, head.envelope->yaw, head.envelope->widen_override);
    apply(env.protrusion, head.envelope->protrusion, head.envelope->widen_override);
  }
  const MandibleEnvelope head_env = env;
  if (head.envelope) check_unmarked_widening(*head.envelope, design, out.problems);
  if (rig.envelope) check_unmarked_widening(*rig.envelope, head_env, out.problems);
  if (rig.envelope) {
    apply(env.pitch, rig.envelope->pitch, rig.envelope->widen_override);
    apply(env.yaw, rig.envelope->yaw, rig.envelope->widen_override);
    apply(env.protrusion, rig.envelope->protrusion, rig.envelope->widen_override);
  }
  for (const Range* r : {&env.pitch, &env.yaw, &env.protrusion}) {
    if (!(r->min <= r->max)) {
      throw ConfigError((rig.envelope ? rig.envelope->where : rig.file) +
                        ": rig.mandible_envelope: expected an envelope that overlaps the "
                        "head's, found an empty intersection");
    }
  }
  check_within_joint_limits(head, rig, env, design, out.problems);
  m.envelope = env;
  m.envelope_widened = !env.within(design) || !env.within(head_env);
  if (!env.within(design)) {
    const std::string where =
        rig.envelope && rig.envelope->widen_override ? rig.envelope->where : head.envelope->where;
    out.warnings.push_back("WARNING: mandible envelope WIDENED beyond the design default by " +
                           where + ": " + describe(env) + " (default: " + describe(design) + ")");
  }
  if (!env.within(head_env)) {
    out.warnings.push_back("WARNING: the rig WIDENS the head's mandible envelope at " +
                           rig.envelope->where + ": " + describe(env) +
                           " (head: " + describe(head_env) + ")");
  }
}

// Coupled face limits: the neutral pose must satisfy them (it is where the
// face goes on stale input, and the projection's fallback), and lie inside
// the bounds.
void set_face_constraints(const HeadConfig& head, const RigConfig& rig, const FaceBounds& b,
                          ControllerModel& m) {
  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    if (m.neutral[i] < b.lo[i] || m.neutral[i] > b.hi[i]) {
      throw ConfigError((head.neutral_where.empty() ? head.file : head.neutral_where) +
                        ": head.neutral: expected a pose inside the envelope and the "
                        "admissible ranges, found " +
                        m.layout.signal(i).name + " = " + std::to_string(m.neutral[i]) +
                        " (SI) outside [" + std::to_string(b.lo[i]) + ", " +
                        std::to_string(b.hi[i]) + "]");
    }
  }
  for (const CoupledLimitConfig& c : rig.coupled_limits) {
    if (c.over_actuators) continue;
    // Checked here, not only in finalize, to name the limit's own line.
    const double at_neutral = c.constraint.value(m.neutral.data());
    if (at_neutral > c.constraint.bound + 1e-12) {  // finalize's tolerance
      throw ConfigError(c.where +
                        ": rig.coupled_limits: expected a limit that the head's neutral pose "
                        "satisfies, found '" +
                        c.constraint.name + "' = " + std::to_string(at_neutral) +
                        " at the neutral pose, above its max " +
                        std::to_string(c.constraint.bound));
    }
    try {
      m.face_constraints.add(c.constraint);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(c.where + ": rig.coupled_limits: " + e.what());
    }
  }
  try {
    m.face_constraints.finalize(m.layout.size(), b.lo.data(), b.hi.data(), m.neutral.data());
  } catch (const std::invalid_argument& e) {
    throw ConfigError(rig.file +
                      ": rig.coupled_limits: expected limits that the head's neutral "
                      "pose satisfies, found " +
                      std::string(e.what()));
  }
}

// Actuators grouped by bus, in bus order then file order. Returns the file
// index of each controller actuator; out.file_order is its inverse.
std::vector<std::size_t> group_by_bus(const RigConfig& rig, BuiltModel& out) {
  std::vector<std::size_t> ordered;
  for (const BusConfig& bus : rig.buses) {
    BusModel bm{bus.name, bus.type, ordered.size(), 0};
    for (std::size_t k = 0; k < rig.actuators.size(); ++k) {
      if (rig.actuators[k].model.bus == bus.name) ordered.push_back(k);
    }
    bm.count = ordered.size() - bm.first;
    out.model.buses.push_back(bm);
  }
  out.file_order.assign(rig.actuators.size(), 0);
  for (std::size_t i = 0; i < ordered.size(); ++i) out.file_order[ordered[i]] = i;
  return ordered;
}

// The reduced face model, when some actuator reads control points; its
// muscles must be the head's, in the head's order.
void load_reduced_if_read(const HeadConfig& head, const RigConfig& rig, ControllerModel& m) {
  const bool reads_points =
      std::any_of(rig.actuators.begin(), rig.actuators.end(),
                  [](const ActuatorConfig& a) { return !a.map.points.empty(); });
  if (!reads_points) return;
  RigMapping& map = m.mapping;
  map.reduced = load_reduced(head);
  if (map.reduced->muscles.size() != m.layout.muscle_count() ||
      map.reduced->control_points.size() > kMaxControlPoints) {
    throw ConfigError(head.file +
                      ": the reduced face model's muscles differ from head.muscles "
                      "(rebuild it with `facectl face reduce`)");
  }
  for (std::size_t k = 0; k < m.layout.muscle_count(); ++k) {
    if (map.reduced->muscles[k] != m.layout.signal(k).name) {
      throw ConfigError(head.file + ": the reduced face model's muscle " + std::to_string(k) +
                        " is '" + map.reduced->muscles[k] + "', head.muscles has '" +
                        m.layout.signal(k).name + "' (rebuild it with `facectl face reduce`)");
    }
  }
}

// Actuator i's terms over the reduced model's control points, by name.
void add_point_terms(std::size_t i, const ActuatorConfig& a, const std::string& who,
                     RigMapping& map) {
  for (const PointTermConfig& p : a.map.points) {
    const auto& names = map.reduced->control_points;
    const auto it = std::find(names.begin(), names.end(), p.point);
    if (it == names.end()) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      throw ConfigError(p.where + ": " + who +
                        ": map.points.point: expected a control point of "
                        "the head (" +
                        list + "), found '" + p.point + "'");
    }
    map.points.push_back({i, static_cast<std::size_t>(it - names.begin()), p.axis, p.gain_si});
  }
}

// What makes actuator i's mapping unusable although it parsed: a refused
// calibration, a linkage of the other unit, nothing driving it.
void check_mapping(std::size_t i, const ActuatorConfig& a, const std::string& who,
                   BuiltModel& out) {
  RigMapping& map = out.model.mapping;
  if (!a.map.calibration_problem.empty()) {
    out.problems.push_back(a.map.calibration_problem + " (" + who + ")");
    map.transforms[i].kind = ChannelTransform::Kind::kNone;  // never run: a problem refuses it
  }
  if (a.map.transform.kind == ChannelTransform::Kind::kLinkage) {
    const Linkage::Kind k = a.map.transform.linkage.kind;
    const bool wants_linear = k == Linkage::Kind::kSliderCrank;
    if (wants_linear != (a.model.kind == ActuatorKind::kLinear)) {
      out.problems.push_back(
          a.map.transform_where + ": " + who + ": a " + std::string(to_string(k)) +
          " linkage drives a " + (wants_linear ? "linear (mm)" : "rotary (deg)") +
          " actuator, but this one is " + yaml_unit(a.model.kind) + " (inconsistent units)");
    }
  }
  if (!map.drives(i)) {
    out.problems.push_back(a.map.where + ": " + who +
                           ": nothing drives it (no non-zero term or point in `map`, and no "
                           "strut of the mandible mechanism)");
  }
}

// Bounds every actuator must respect whatever the input: a finite mapping
// and a latency the simulated twin can hold.
void check_actuator_bounds(const ActuatorConfig& a, const FaceBounds& b,
                           const RuntimeConfig& runtime) {
  // The mapping must stay finite over every admissible input (an overflow
  // would be a NaN command); `facectl verify` proves the tighter ranges.
  double reach = std::fabs(a.map.offset_si);
  for (const MappingTerm& t : a.map.terms) {
    reach += std::fabs(t.gain_si) * std::max(std::fabs(b.lo[t.signal]), std::fabs(b.hi[t.signal]));
  }
  if (!std::isfinite(reach) || reach > 1e3) {
    throw ConfigError(a.map.where + ": rig.actuators '" + a.model.name +
                      "'.map: expected gains and offset that keep the command finite and "
                      "physical (|command| <= 1000 SI units), found a reach of " +
                      std::to_string(reach));
  }
  // The simulated twin's delay line holds 64 commands.
  if (a.plant.latency_s * runtime.rate_hz >= 60.0) {
    throw ConfigError(a.plant_where + ": rig.actuators '" + a.model.name +
                      "'.plant.latency_ms: expected less than 60 ticks of latency at " +
                      std::to_string(runtime.rate_hz) + " Hz, found " +
                      std::to_string(a.plant.latency_s * 1e3) + " ms");
  }
}

// The rig mapping: the mandible mechanism, then each actuator in controller
// order (its model, linear terms, control-point terms and transform).
void set_mapping(const HeadConfig& head, const RigConfig& rig, const RuntimeConfig& runtime,
                 const std::vector<std::size_t>& ordered, const FaceBounds& b, BuiltModel& out) {
  ControllerModel& m = out.model;
  RigMapping& map = m.mapping;
  map.linear = LinearMapping(rig.actuators.size(), m.layout.size());
  map.transforms.resize(rig.actuators.size());
  map.muscle_count = m.layout.muscle_count();
  map.jaw_pitch = m.layout.jaw_pitch();
  map.jaw_yaw = m.layout.jaw_yaw();
  map.jaw_protrusion = m.layout.jaw_protrusion();
  map.eyelid_closure[0] = m.layout.eyelid_closure(0);
  map.eyelid_closure[1] = m.layout.eyelid_closure(1);
  build_mechanism(head, rig, out.file_order, m, out.problems);
  load_reduced_if_read(head, rig, m);
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    const ActuatorConfig& a = rig.actuators[ordered[i]];
    const std::string who = "actuator '" + a.model.name + "'";
    m.actuators.push_back(a.model);
    m.protection.push_back(a.protection);
    map.linear.set_offset(i, a.map.offset_si);
    for (const MappingTerm& t : a.map.terms) map.linear.set_gain(i, t.signal, t.gain_si);
    add_point_terms(i, a, who, map);
    map.transforms[i] = a.map.transform;
    check_mapping(i, a, who, out);
    check_actuator_bounds(a, b, runtime);
  }
  finish_points(map);
}

// Actuator coupled limits, over controller order; rest must satisfy them
// (it is where STOPPING goes, and the projection's fallback).
void set_actuator_constraints(const RigConfig& rig, BuiltModel& out) {
  ControllerModel& m = out.model;
  std::array<double, kMaxActuators> act_lo{}, act_hi{}, rest{};
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    act_lo[i] = m.actuators[i].limits.soft_min;
    act_hi[i] = m.actuators[i].limits.soft_max;
    rest[i] = m.actuators[i].rest;
  }
  for (const CoupledLimitConfig& c : rig.coupled_limits) {
    if (!c.over_actuators) continue;
    CoupledConstraints::Constraint k = c.constraint;
    for (std::size_t t = 0; t < k.terms; ++t) k.index[t] = out.file_order[k.index[t]];
    // Checked here, not only in finalize, to name the limit's own line.
    const double at_rest = k.value(rest.data());
    if (at_rest > k.bound + 1e-12) {  // finalize's tolerance
      throw ConfigError(c.where +
                        ": rig.coupled_limits: expected a limit that every actuator's rest "
                        "position satisfies, found '" +
                        k.name + "' = " + std::to_string(at_rest) + " at rest, above its max " +
                        std::to_string(k.bound));
    }
    try {
      m.actuator_constraints.add(k);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(c.where + ": rig.coupled_limits: " + e.what());
    }
  }
  try {
    m.actuator_constraints.finalize(m.actuators.size(), act_lo.data(), act_hi.data(), rest.data());
  } catch (const std::invalid_argument& e) {
    throw ConfigError(rig.file +
                      ": rig.coupled_limits: expected actuator limits that every actuator's "
                      "rest position satisfies, found " +
                      std::string(e.what()));
  }
}

}  // namespace

FaceBounds face_bounds(const ControllerModel& m) {
  FaceBounds b;
  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    Range r = m.admissible[i];
    if (i == m.layout.jaw_pitch()) r = m.envelope.pitch;
    if (i == m.layout.jaw_yaw()) r = m.envelope.yaw;
    if (i == m.layout.jaw_protrusion()) r = m.envelope.protrusion;
    b.lo[i] = r.min;
    b.hi[i] = r.max;
  }
  return b;
}

BuiltModel build_model(const HeadConfig& head, const RigConfig& rig, const RuntimeConfig& runtime) {
  BuiltModel out;
  ControllerModel& m = out.model;
  set_face_signals(head, m);
  m.rate_hz = runtime.rate_hz;
  m.safety = runtime.safety;
  m.shaping = runtime.shaping;
  set_envelope(head, rig, out);
  const FaceBounds bounds = face_bounds(m);
  set_face_constraints(head, rig, bounds, m);
  const std::vector<std::size_t> ordered = group_by_bus(rig, out);
  set_mapping(head, rig, runtime, ordered, bounds, out);
  set_actuator_constraints(rig, out);
  return out;
}

}  // namespace facectl
