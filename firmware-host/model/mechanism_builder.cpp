#include "firmware-host/model/mechanism_builder.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "control/analysis/mechanism_rate_bounds.hpp"
#include "control/units.hpp"
#include "facectl/face/face_model.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/input_error.hpp"

namespace facectl {
namespace {

std::string fmt(const char* f, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}

// A DOF the struts do not drive must not be asked for: the face would think
// the jaw went somewhere it did not.
void check_held(const MandibleMechanism& mech, const MandibleEnvelope& env,
                const std::string& where, std::vector<std::string>& problems) {
  struct Axis {
    MandibleDof dof;
    Range range;
    double held, unit;
    const char* name;
  };
  const Axis axes[] = {
      {MandibleDof::kPitch, env.pitch, mech.held.pitch_rad, kDeg, "pitch_deg"},
      {MandibleDof::kYaw, env.yaw, mech.held.yaw_rad, kDeg, "yaw_deg"},
      {MandibleDof::kProtrusion, env.protrusion, mech.held.protrusion_m, 1e-3, "protrusion_mm"}};
  for (const Axis& a : axes) {
    if (mech.driven[static_cast<std::size_t>(a.dof)]) continue;
    if (a.range.min == a.held && a.range.max == a.held) continue;
    problems.push_back(where + ": mandible_mechanism: the struts hold " + a.name + " at " +
                       fmt("%.4g", a.held / a.unit) + " but the envelope allows " +
                       fmt("%.4g", a.range.min / a.unit) + ".." +
                       fmt("%.4g", a.range.max / a.unit) + ": narrow rig.mandible_envelope." +
                       a.name + " to the held value");
  }
}

std::size_t file_index(const RigConfig& rig, const std::string& name) {
  std::size_t k = 0;
  while (k < rig.actuators.size() && rig.actuators[k].model.name != name) ++k;
  return k;
}

const char* reaction_name(FaultReaction r) {
  return r == FaultReaction::kRelax ? "relax" : r == FaultReaction::kHold ? "hold" : "rest";
}

}  // namespace

face::MandibleAxes load_mandible_axes(const HeadConfig& head) {
  const std::string dir = head.file.substr(0, head.file.find_last_of('/') + 1);
  try {
    return face::build_face_model(face::load_head_spec(dir.empty() ? "." : dir)).axes;
  } catch (const face::InputError& e) {
    throw ConfigError(std::string(e.what()) + " (the rig's mandible mechanism needs its axes)");
  }
}

void build_mechanism(const HeadConfig& head, const RigConfig& rig,
                     const std::vector<std::size_t>& file_order, ControllerModel& m,
                     std::vector<std::string>& problems) {
  if (!rig.mechanism) return;
  const MandibleMechanismConfig& cfg = *rig.mechanism;
  std::vector<MandibleStrut> struts;
  MandibleStrokes rest_strokes{};
  bool rest_is_stroke_at_rest = true;
  for (const StrutConfig& s : cfg.struts) {
    const std::size_t k = file_index(rig, s.actuator);
    if (k == rig.actuators.size()) {
      throw ConfigError(s.where + ": rig.mandible_mechanism.struts.actuator: expected the name " +
                        "of an actuator of this rig, found '" + s.actuator + "'");
    }
    const ActuatorConfig& a = rig.actuators[k];
    if (a.model.kind != ActuatorKind::kLinear) {
      throw ConfigError(s.where + ": rig.mandible_mechanism.struts: expected a linear (mm) " +
                        "actuator for a strut, found '" + s.actuator + "', which is rotary (deg)");
    }
    if (a.has_map) {
      throw ConfigError(a.map.where + ": rig.actuators '" + s.actuator +
                        "'.map: expected no `map` for a strut of the mandible mechanism (" +
                        s.where + "), found one");
    }
    // The struts move together by IK, so in FAULT they react together.
    const ActuatorConfig& first = rig.actuators[file_index(rig, cfg.struts.front().actuator)];
    if (a.model.fault_reaction != first.model.fault_reaction) {
      throw ConfigError(a.fault_reaction_where + ": rig.actuators '" + s.actuator +
                        "'.fault_reaction: expected the same reaction as the mechanism's first " +
                        "strut '" + first.model.name + "' (" + first.fault_reaction_where +
                        "), found " + reaction_name(a.model.fault_reaction));
    }
    MandibleStrut strut;
    strut.actuator = file_order[k];
    strut.skull = s.skull;
    strut.mandible = s.mandible;
    strut.stroke = {a.model.limits.soft_min, a.model.limits.soft_max};
    strut.stroke_at_rest = s.stroke_at_rest.value_or(a.model.rest);
    rest_strokes[struts.size()] = a.model.rest;
    rest_is_stroke_at_rest = rest_is_stroke_at_rest && a.model.rest == strut.stroke_at_rest;
    struts.push_back(strut);
  }
  try {
    m.mapping.mechanism = make_mandible_mechanism(load_mandible_axes(head), cfg.dofs, struts,
                                                  m.envelope, cfg.held, cfg.metric);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(cfg.where + ": rig.mandible_mechanism: " + e.what());
  }
  const MandibleMechanism& mech = *m.mapping.mechanism;
  check_held(mech, m.envelope, cfg.where, problems);
  // The mandible's own limits: position = the envelope, rates from the rig.
  const Range* axis[3] = {&m.envelope.pitch, &m.envelope.yaw, &m.envelope.protrusion};
  for (std::size_t k = 0; k < 3; ++k) {
    m.mandible_limits[k] = cfg.limits[k];
    m.mandible_limits[k].position_min = m.mandible_limits[k].soft_min = axis[k]->min;
    m.mandible_limits[k].position_max = m.mandible_limits[k].soft_max = axis[k]->max;
  }
  // Moving within those rates, no strut may need more than its own limits.
  for (std::size_t i = 0; i < mech.struts(); ++i) {
    const StrutDemand need = strut_demand(mech, i, m.envelope, m.mandible_limits);
    const ActuatorLimits& l = rig.actuators[file_index(rig, cfg.struts[i].actuator)].model.limits;
    if (need.velocity > l.max_velocity || need.acceleration > l.max_acceleration) {
      problems.push_back(
          cfg.limits_where + ": mandible_mechanism.limits: moving at these rates " +
          "can ask strut '" + cfg.struts[i].actuator + "' for " + fmt("%.4g", need.velocity * 1e3) +
          " mm/s and " + fmt("%.4g", need.acceleration * 1e3) + " mm/s^2, beyond its " +
          fmt("%.4g", l.max_velocity * 1e3) + " mm/s and " + fmt("%.4g", l.max_acceleration * 1e3) +
          " mm/s^2: lower the mandible's rates or raise the strut's limits");
    }
  }
  m.mandible_rest = to_pose(mech.held_in(MandibleVector::Zero()));
  // STOPPING sends every actuator to its rest: the struts' rests must be one
  // pose of the mandible inside the envelope, or they fight each other.
  if (!rest_is_stroke_at_rest) {
    const auto pose = forward(mech, rest_strokes);
    if (pose) m.mandible_rest = *pose;
    const bool inside = pose && pose->pitch_rad >= m.envelope.pitch.min - 1e-9 &&
                        pose->pitch_rad <= m.envelope.pitch.max + 1e-9 &&
                        pose->yaw_rad >= m.envelope.yaw.min - 1e-9 &&
                        pose->yaw_rad <= m.envelope.yaw.max + 1e-9 &&
                        pose->protrusion_m >= m.envelope.protrusion.min - 1e-12 &&
                        pose->protrusion_m <= m.envelope.protrusion.max + 1e-12;
    if (!inside) {
      problems.push_back(cfg.where +
                         ": mandible_mechanism: the struts' rest positions are no mandible pose "
                         "inside the envelope, so going to rest would force the mechanism: set "
                         "each strut's rest_mm to its stroke_at_rest_mm");
    }
  }
}

}  // namespace facectl
