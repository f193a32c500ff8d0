#include "firmware-host/model_builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "firmware-host/config_node.hpp"

namespace facectl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

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

}  // namespace

BuiltModel build_model(const HeadConfig& head, const RigConfig& rig, const RuntimeConfig& runtime) {
  BuiltModel out;
  ControllerModel& m = out.model;
  m.layout = head.layout;
  m.neutral = head.neutral;
  m.rate_hz = runtime.rate_hz;
  m.safety = runtime.safety;
  m.shaping = runtime.shaping;

  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    const SignalInfo& info = m.layout.signal(i);
    m.admissible[i] = {info.domain_min, info.domain_max};
    if (auto it = head.rigid_ranges.find(info.name); it != head.rigid_ranges.end()) {
      m.admissible[i] = it->second;
    }
  }

  // Envelope, axis by axis: the design default, then the head's, then the
  // rig's. A stated axis narrows (intersects) unless its block carries
  // `widen_override`, in which case it replaces. Anything wider than the
  // design default, or than the head's own envelope, is announced loudly.
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

  // Coupled face limits: the neutral pose must satisfy them (it is where the
  // face goes on stale input, and the projection's fallback).
  std::array<double, kMaxFaceSignals> lo{};
  std::array<double, kMaxFaceSignals> hi{};
  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    Range r = m.admissible[i];
    if (i == m.layout.jaw_pitch()) r = env.pitch;
    if (i == m.layout.jaw_yaw()) r = env.yaw;
    if (i == m.layout.jaw_protrusion()) r = env.protrusion;
    lo[i] = r.min;
    hi[i] = r.max;
  }
  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    if (m.neutral[i] < lo[i] || m.neutral[i] > hi[i]) {
      throw ConfigError(head.file +
                        ": head.neutral: expected a pose inside the envelope and the "
                        "admissible ranges, found " +
                        m.layout.signal(i).name + " = " + std::to_string(m.neutral[i]) +
                        " (SI) outside [" + std::to_string(lo[i]) + ", " + std::to_string(hi[i]) +
                        "]");
    }
  }
  for (const CoupledLimitConfig& c : rig.coupled_limits) {
    try {
      m.face_constraints.add(c.constraint);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(c.where + ": rig.coupled_limits: " + e.what());
    }
  }
  try {
    m.face_constraints.finalize(m.layout.size(), lo.data(), hi.data(), m.neutral.data());
  } catch (const std::invalid_argument& e) {
    throw ConfigError(rig.file +
                      ": rig.coupled_limits: expected limits that the head's neutral "
                      "pose satisfies, found " +
                      std::string(e.what()));
  }

  // Actuators grouped by bus, in bus order then file order.
  m.mapping = LinearMapping(rig.actuators.size(), m.layout.size());
  std::vector<const ActuatorConfig*> ordered;
  for (const BusConfig& bus : rig.buses) {
    BusModel bm{bus.name, bus.type, ordered.size(), 0};
    for (const ActuatorConfig& a : rig.actuators) {
      if (a.model.bus == bus.name) ordered.push_back(&a);
    }
    bm.count = ordered.size() - bm.first;
    m.buses.push_back(bm);
  }
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    const ActuatorConfig& a = *ordered[i];
    m.actuators.push_back(a.model);
    m.mapping.set_offset(i, a.map_offset_si);
    for (const MappingTerm& t : a.terms) m.mapping.set_gain(i, t.signal, t.gain_si);
    if (!m.mapping.drives(i)) {
      throw ConfigError(a.map_where + ": rig.actuators '" + a.model.name +
                        "'.map.terms: expected at least one non-zero mapping term, found none "
                        "(an actuator that nothing drives)");
    }
    // The mapping must stay finite over every admissible input (an overflow
    // would be a NaN command); `facectl verify` proves the tighter ranges.
    double reach = std::fabs(a.map_offset_si);
    for (const MappingTerm& t : a.terms) {
      reach += std::fabs(t.gain_si) * std::max(std::fabs(lo[t.signal]), std::fabs(hi[t.signal]));
    }
    if (!std::isfinite(reach) || reach > 1e3) {
      throw ConfigError(a.map_where + ": rig.actuators '" + a.model.name +
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
  return out;
}

}  // namespace facectl
