#include "firmware-host/verify/static_proof.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "control/units.hpp"
#include "drivers/protocol/cia402_counts.hpp"
#include "drivers/protocol/wire_encoding.hpp"
#include "firmware-host/verify/mechanism_channels.hpp"
#include "firmware-host/verify/point_channels.hpp"

namespace facectl::verify {
namespace {

using Severity = Finding::Severity;

std::string fmt(const char* f, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}

// An LP optimum sits on a vertex, so signals the objective ignores land on
// arbitrary bounds. Put the ones no constraint ties to the rest back at
// neutral: the witness then shows only what matters (and stays admissible).
std::vector<double> tidy(const ControllerModel& m, const Polytope& set,
                         const std::vector<double>& objective, std::vector<double> x) {
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (objective[j] != 0.0) continue;
    bool tied = false;
    for (const auto& row : set.rows) tied = tied || row[j] != 0.0;
    if (!tied) x[j] = std::clamp(m.neutral[j], set.lo[j], set.hi[j]);
  }
  return x;
}

struct EffectorRange {
  double lo, hi;
  std::vector<double> at_lo, at_hi;  // witnesses (face inputs), if known
};

// The effector's range over the admissible set: exact (LP) for a channel that
// is linear in the face signals.
std::optional<EffectorRange> linear_effector_range(const ControllerModel& m, const Polytope& set,
                                                   std::size_t actuator) {
  std::vector<double> c(m.layout.size());
  for (std::size_t j = 0; j < c.size(); ++j) c[j] = m.mapping.linear.gain(actuator, j);
  const auto hi = maximize(set, c);
  const auto lo = minimize(set, c);
  if (!hi || !lo) return std::nullopt;
  const double off = m.mapping.linear.offset(actuator);
  return EffectorRange{lo->value + off, hi->value + off, tidy(m, set, c, lo->at),
                       tidy(m, set, c, hi->at)};
}

// The transform of an effector range. Calibration curves are monotone, so the
// ends map to the ends. A linkage inverse is checked numerically for
// monotony over the range (`proven` turns false) and its ends are used.
EffectorRange transform_range(const ChannelTransform& t, EffectorRange e, const std::string& who,
                              const std::string& unit, double scale, bool* proven,
                              std::vector<Finding>& findings, const ControllerModel& m) {
  auto hull = [](double a, double b, EffectorRange in) {
    const bool swap = a > b;
    return EffectorRange{swap ? b : a, swap ? a : b, swap ? in.at_hi : in.at_lo,
                         swap ? in.at_lo : in.at_hi};
  };
  if (t.kind == ChannelTransform::Kind::kNone) return e;
  if (t.kind == ChannelTransform::Kind::kCalibration) {
    if (e.lo < t.curve.x_min() || e.hi > t.curve.x_max()) {
      findings.push_back({Severity::kWarn, "calibration domain", who,
                          "the effector reaches beyond the calibration curve's points, where "
                          "the command is held at the curve's end (a clamp)",
                          describe_face(m, e.lo < t.curve.x_min() ? e.at_lo : e.at_hi)});
    }
    return hull(t.curve.evaluate(e.lo), t.curve.evaluate(e.hi), e);
  }
  const Linkage& l = t.linkage;
  if (e.lo < l.effector_min || e.hi > l.effector_max) {
    findings.push_back({Severity::kWarn, "linkage range", who,
                        "the effector reaches beyond the linkage's working range, where the "
                        "command is held at the range's end (a clamp)",
                        describe_face(m, e.lo < l.effector_min ? e.at_lo : e.at_hi)});
  }
  const double a = std::clamp(e.lo, l.effector_min, l.effector_max);
  const double b = std::clamp(e.hi, l.effector_min, l.effector_max);
  constexpr int kSamples = 4096;
  double prev = 0.0, dir = 0.0;
  for (int k = 0; k <= kSamples; ++k) {
    const double x = a + (b - a) * k / kSamples;
    const auto y = l.to_actuator(x);
    if (!y) {
      findings.push_back({Severity::kFail, "linkage closure", who,
                          "the linkage cannot close at effector " + fmt("%.4g", x) +
                              " (SI) inside its working range",
                          ""});
      return e;
    }
    if (k > 0) {
      const double d = *y - prev;
      if (dir == 0.0) dir = d;
      if (d * dir < 0.0) {
        findings.push_back({Severity::kFail, "linkage monotone", who,
                            "the linkage's inverse turns back inside the working range, at " +
                                fmt("%.4g", *y * scale) + " " + unit,
                            ""});
      }
    }
    prev = *y;
  }
  *proven = false;
  return hull(*l.to_actuator(a), *l.to_actuator(b), e);
}

// The bus that carries an actuator, if it is a CiA 402 one.
const BusConfig* cia402_bus(const RigConfig& rig, const ActuatorModel& a) {
  const auto it = std::find_if(rig.buses.begin(), rig.buses.end(),
                               [&](const BusConfig& b) { return b.name == a.bus; });
  return it != rig.buses.end() && it->is_cia402() ? &*it : nullptr;
}

// The hardware range must encode strictly inside the raw type the driver
// sends (its saturation limits: a value that reaches one is clipped). A CiA
// 402 drive counts in int32 with the actuator's encoding or the bus's counts.
void check_encoding(const ActuatorModel& a, const BusConfig* drive_bus, const std::string& who,
                    std::vector<Finding>& findings) {
  const double scale = yaml_per_si(a.kind);
  const ActuatorEncoding& e = a.encoding;
  const ActuatorEncoding::Raw type = drive_bus ? ActuatorEncoding::Raw::kInt32 : e.raw;
  std::optional<cia402::DriveCounts> counts;
  if (drive_bus) {
    try {
      counts = cia402::drive_counts(a, drive_bus->can);
    } catch (const std::invalid_argument& error) {
      findings.push_back({Severity::kFail, "encoding", who, error.what(), ""});
      return;
    }
  }
  const double lo = raw_min(type), hi = raw_max(type);
  for (double v : {a.limits.position_min, a.limits.position_max}) {
    const double raw =
        counts ? v * counts->per_si + counts->offset : v * scale * e.scale + e.offset;
    if (raw <= lo || raw >= hi) {  // strictly inside, as the loader requires
      findings.push_back({Severity::kFail, "encoding", who,
                          "the hardware range does not fit raw " + std::string(raw_name(type)) +
                              ": position " + fmt("%.4g", v * scale) + " encodes to " +
                              fmt("%.0f", raw) + " counts, outside [" + fmt("%.0f", lo) + ", " +
                              fmt("%.0f", hi) + "]",
                          ""});
    }
  }
}

// The rig's limits against what the actuator's servo can do (its `plant:`
// block, the only servo spec the rig carries; docs/CONFIG.md "Plant"): the
// limiter would command motion the servo cannot follow.
void check_capability(const LoadedConfig& cfg, std::vector<Finding>& findings) {
  for (const ActuatorConfig& ac : cfg.rig.actuators) {
    const ActuatorLimits& l = ac.model.limits;
    const sim::ServoPlantParams& servo = ac.plant;
    const double scale = yaml_per_si(ac.model.kind);
    const std::string u = yaml_unit(ac.model.kind);
    auto check = [&](double rig, double can, const std::string& key, const std::string& unit) {
      if (can <= 0.0 || rig <= can * (1.0 + 1e-12)) return;  // 0: the servo has no such limit
      findings.push_back({Severity::kFail, "capability", ac.model.name,
                          key + " " + fmt("%.6g", rig * scale) + " " + unit + " > the servo's " +
                              fmt("%.6g", can * scale) + " " + unit + " (plant " + key + ", " +
                              ac.plant_where +
                              "): the limiter would command what the servo "
                              "cannot follow; lower the rig's limit or fit a faster servo",
                          ""});
    };
    check(l.max_velocity, servo.max_velocity, "max_velocity_" + u + "_s", u + "/s");
    check(l.max_acceleration, servo.max_acceleration, "max_acceleration_" + u + "_s2", u + "/s^2");
  }
}

// Each `expect_direction`: with the other signals at neutral, the mapped
// command must move the expected way on every step across the signal's
// admissible range, and move at all. A channel that reads control points goes
// through the reduced model, a fit: where the full model flattens (a sheet
// muscle's pull has zero slope at c = 1) the fit may turn back a little (the
// default rig's outer brows, 0.14 and 0.17 deg of 90 as frontalis_outer goes from
// 0.95 to 1, 0.06-0.07 mm of brow, under the fit's 0.14 mm RMS for one muscle). A
// turn back, from the best so far, smaller than kDirectionSlack of the actuator's
// hardware range (about a hobby servo's deadband), beside a real move the expected
// way (at least that slack and ten times the turn back), is a warning, not a failure;
// a flipped or miswired mapping turns back over most of its range, and a signal that
// only stirs fit noise makes no real move.
constexpr double kDirectionSlack = 2.5e-3;

void check_directions(const LoadedConfig& cfg, const Polytope& set,
                      std::vector<Finding>& findings) {
  const ControllerModel& m = cfg.built.model;
  MappingWorkspace w = make_mapping_workspace(m.mapping);
  std::array<double, kMaxFaceSignals> face{};
  std::array<double, kMaxActuators> out{};
  for (std::size_t k = 0; k < cfg.rig.actuators.size(); ++k) {
    const ActuatorConfig& ac = cfg.rig.actuators[k];
    const std::size_t i = cfg.built.file_order[k];
    const double scale = yaml_per_si(ac.model.kind);
    const std::string unit = yaml_unit(ac.model.kind);
    for (const DirectionExpectation& e : ac.expect_direction) {
      for (std::size_t j = 0; j < set.size(); ++j) {
        face[j] = std::clamp(m.neutral[j], set.lo[j], set.hi[j]);
      }
      const double lo = set.lo[e.signal], hi = set.hi[e.signal];
      const double to_file = 1.0 / yaml_to_si(m.layout.signal(e.signal).kind);
      constexpr int kSteps = 64;
      // fell: the largest distance the command comes back below its best so far; rise:
      // how far that best lies beyond the start.
      double prev = 0.0, moved = 0.0, fell = 0.0, best = 0.0, start = 0.0;
      std::optional<std::pair<double, double>> wrong;  // signal values, SI
      double wrong_from = 0.0, wrong_to = 0.0;
      for (int s = 0; s <= kSteps; ++s) {
        face[e.signal] = lo + (hi - lo) * s / kSteps;
        map_to_actuators(m.mapping, w, face, out);
        if (s > 0) {
          const double d = (out[i] - prev) * e.sign;
          const double tol = 1e-9 * (1.0 + std::fabs(out[i]) + std::fabs(prev));
          if (d < -tol && !wrong) {
            wrong = std::pair{face[e.signal] - (hi - lo) / kSteps, face[e.signal]};
            wrong_from = prev;
            wrong_to = out[i];
          }
          if (d > tol) moved = 1.0;
        }
        if (s == 0) start = out[i] * e.sign;
        best = s == 0 ? start : std::max(best, out[i] * e.sign);
        fell = std::max(fell, best - out[i] * e.sign);
        prev = out[i];
      }
      const std::string expected =
          std::string(e.sign > 0 ? "expected to rise" : "expected to fall") + " with " + e.key +
          " (expect_direction " + (e.sign > 0 ? "+1" : "-1") + ")";
      const double range = ac.model.limits.position_max - ac.model.limits.position_min;
      const double slack = kDirectionSlack * range, rise = best - start;
      const bool slight = fell < slack && rise >= std::max(slack, 10 * fell);
      if (wrong) {
        findings.push_back(
            {slight ? Severity::kWarn : Severity::kFail, "direction", ac.model.name,
             expected + ", but it " + (e.sign > 0 ? "falls" : "rises") +
                 (slight ? " slightly (by at most " + fmt("%.3g", fell * scale) + " " + unit +
                               ", under " + fmt("%.2g", 100 * kDirectionSlack) +
                               "% of its hardware range)"
                         : std::string()) +
                 ": " + fmt("%.4g", wrong_from * scale) + " -> " + fmt("%.4g", wrong_to * scale) +
                 " " + unit + " as " + e.key + " goes " + fmt("%.4g", wrong->first * to_file) +
                 " -> " + fmt("%.4g", wrong->second * to_file) +
                 ", the other signals at neutral (" + e.where + ")",
             ""});
      } else if (moved == 0.0) {
        findings.push_back({Severity::kFail, "direction", ac.model.name,
                            expected + ", but it does not move with it over " +
                                fmt("%.4g", lo * to_file) + ".." + fmt("%.4g", hi * to_file) +
                                ", the other signals at neutral (" + e.where + ")",
                            ""});
      }
    }
  }
}

}  // namespace

Polytope admissible_face_set(const ControllerModel& m) {
  Polytope p;
  const std::size_t n = m.layout.size();
  for (std::size_t i = 0; i < n; ++i) {
    Range r = m.admissible[i];
    if (i == m.layout.jaw_pitch()) r = m.envelope.pitch;
    if (i == m.layout.jaw_yaw()) r = m.envelope.yaw;
    if (i == m.layout.jaw_protrusion()) r = m.envelope.protrusion;
    p.lo.push_back(r.min);
    p.hi.push_back(r.max);
  }
  for (std::size_t c = 0; c < m.face_constraints.size(); ++c) {
    const auto& k = m.face_constraints.constraint(c);
    std::vector<double> row(n, 0.0);
    for (std::size_t t = 0; t < k.terms; ++t) row[k.index[t]] += k.coeff[t];
    p.rows.push_back(row);
    p.rhs.push_back(k.bound);
  }
  return p;
}

std::string describe_face(const ControllerModel& m, const std::vector<double>& x) {
  std::string out;
  for (std::size_t i = 0; i < x.size() && i < m.layout.size(); ++i) {
    if (std::fabs(x[i] - m.neutral[i]) < 1e-12) continue;
    const SignalInfo& s = m.layout.signal(i);
    out += (out.empty() ? "" : ", ") + yaml_key(s) + "=" + fmt("%.4g", x[i] / yaml_to_si(s.kind));
  }
  return out.empty() ? "the neutral pose" : out;
}

StaticProof prove(const LoadedConfig& cfg) {
  const auto start = std::chrono::steady_clock::now();
  const ControllerModel& m = cfg.built.model;
  StaticProof out;
  for (const std::string& p : cfg.built.problems) {
    out.findings.push_back({Severity::kFail, "rig", "", p, ""});
  }
  const Polytope set = admissible_face_set(m);
  if (!maximize(set, std::vector<double>(set.size(), 0.0))) {
    out.findings.push_back({Severity::kFail, "admissible set", "",
                            "the coupled face limits leave no admissible face at all", ""});
    return out;
  }

  // Antagonists the head declares must not be driven together past max_sum.
  for (const AntagonistPair& pair : cfg.head.antagonists) {
    std::vector<double> c(set.size(), 0.0);
    c[pair.a] = c[pair.b] = 1.0;
    const auto worst = maximize(set, c);
    const std::string who = m.layout.signal(pair.a).name + " + " + m.layout.signal(pair.b).name;
    if (worst && worst->value > pair.max_sum + 1e-9) {
      out.findings.push_back({Severity::kFail, "antagonists", who,
                              "co-activation reaches " + fmt("%.3g", worst->value) + " > max_sum " +
                                  fmt("%.3g", pair.max_sum) + " (" + pair.where +
                                  "): add a coupled face limit",
                              describe_face(m, tidy(m, set, c, worst->at))});
    } else if (worst) {
      out.findings.push_back({Severity::kInfo, "antagonists", who,
                              "co-activation at most " + fmt("%.3g", worst->value) +
                                  " <= max_sum " + fmt("%.3g", pair.max_sum),
                              ""});
    }
  }

  const std::vector<MechanismChannel> struts = mechanism_channels(m, set);
  auto strut_of = [&](std::size_t i) {
    return std::find_if(struts.begin(), struts.end(),
                        [&](const MechanismChannel& c) { return c.actuator == i; });
  };
  // The channels that read control points: branch and bound on the reduced model.
  std::vector<std::size_t> point_actuators;
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    const bool reads_points = std::any_of(m.mapping.points.begin(), m.mapping.points.end(),
                                          [&](const PointTerm& p) { return p.actuator == i; });
    if (reads_points && strut_of(i) == struts.end()) point_actuators.push_back(i);
  }
  const std::vector<PointChannel> points = point_channels(m, set, point_actuators);
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    const ActuatorModel& a = m.actuators[i];
    const std::string who = a.name;
    const double scale = yaml_per_si(a.kind);
    ActuatorRange r;
    r.name = a.name;
    r.unit = yaml_unit(a.kind);
    r.hardware_min = a.limits.position_min * scale;
    r.hardware_max = a.limits.position_max * scale;
    r.soft_min = a.limits.soft_min * scale;
    r.soft_max = a.limits.soft_max * scale;
    check_encoding(a, cia402_bus(cfg.rig, a), who, out.findings);
    if (a.max_current_a > 0.0) {
      out.findings.push_back({Severity::kInfo, "current", who,
                              "max_current_a is declared but not checked: no bus backend "
                              "reports current yet",
                              ""});
    }

    std::optional<EffectorRange> effector;
    bool proven = true;
    const auto strut = strut_of(i);
    const auto point = std::find_if(points.begin(), points.end(),
                                    [&](const PointChannel& c) { return c.actuator == i; });
    if (strut != struts.end()) {
      effector = EffectorRange{strut->lo, strut->hi, strut->at_lo, strut->at_hi};
      r.method = strut->converged
                     ? "branch and bound on the mandible mechanism"
                     : "branch and bound on the mandible mechanism (budget hit: loose bound)";
    } else if (point != points.end()) {
      if (!point->empty) effector = EffectorRange{point->lo, point->hi, point->at_lo, point->at_hi};
      r.method = point->converged
                     ? "branch and bound on the reduced model"
                     : "branch and bound on the reduced model (budget hit: loose bound)";
    } else {
      effector = linear_effector_range(m, set, i);
      r.method = "exact LP (GLPK, rational)";
    }
    if (!effector) continue;
    const EffectorRange act = transform_range(m.mapping.transforms[i], *effector, who, r.unit,
                                              scale, &proven, out.findings, m);
    if (!proven) r.method += " + numerically monotone linkage";
    r.proven = proven;
    r.lo = act.lo * scale;
    r.hi = act.hi * scale;
    r.at_lo = act.at_lo;
    r.at_hi = act.at_hi;
    r.hardware_margin = std::min(r.lo - r.hardware_min, r.hardware_max - r.hi);
    r.soft_margin = std::min(r.lo - r.soft_min, r.soft_max - r.hi);
    const double eps = 1e-9 * std::max(1.0, r.hardware_max - r.hardware_min);  // rounding
    if (r.hi > r.hardware_max + eps || r.lo < r.hardware_min - eps) {
      const bool high = r.hi > r.hardware_max;
      out.findings.push_back({Severity::kFail, "hardware range", who,
                              "mapped command reaches " + fmt("%.4g", high ? r.hi : r.lo) + " " +
                                  r.unit + (high ? " > hardware max " : " < hardware min ") +
                                  fmt("%.4g", high ? r.hardware_max : r.hardware_min) + " " +
                                  r.unit + " (position limit, by " +
                                  fmt("%.4g", -r.hardware_margin) + " " + r.unit + ")",
                              describe_face(m, high ? act.at_hi : act.at_lo)});
    } else if (r.soft_margin < -1e-9 * std::max(1.0, r.soft_max - r.soft_min)) {
      const bool high = r.hi > r.soft_max;
      out.findings.push_back({Severity::kWarn, "soft range", who,
                              "mapped command reaches " + fmt("%.4g", high ? r.hi : r.lo) + " " +
                                  r.unit + ", beyond the soft limit " +
                                  fmt("%.4g", high ? r.soft_max : r.soft_min) + " " + r.unit +
                                  ": the limiter will clamp it there",
                              describe_face(m, high ? act.at_hi : act.at_lo)});
    }
    out.actuators.push_back(r);
  }

  // Actuator coupled limits: will the projection have to act? Exact where every
  // actuator in the limit maps linearly.
  for (std::size_t c = 0; c < m.actuator_constraints.size(); ++c) {
    const auto& k = m.actuator_constraints.constraint(c);
    std::vector<double> obj(set.size(), 0.0);
    double offset = 0.0;
    bool linear = true;
    for (std::size_t t = 0; t < k.terms; ++t) {
      const std::size_t act = k.index[t];
      linear = linear && m.mapping.transforms[act].kind == ChannelTransform::Kind::kNone;
      for (std::size_t j = 0; j < obj.size(); ++j) {
        obj[j] += k.coeff[t] * m.mapping.linear.gain(act, j);
      }
      offset += k.coeff[t] * m.mapping.linear.offset(act);
    }
    if (!linear) continue;
    const auto worst = maximize(set, obj);
    if (!worst) continue;
    const double excess = worst->value + offset - k.bound;
    out.findings.push_back({Severity::kInfo, "actuator coupled limit", k.name,
                            excess > 1e-9 ? "the mapping can ask for " + fmt("%.4g", excess) +
                                                " beyond it; the tick projects such targets, and "
                                                "position bounds keep every step inside it"
                                          : "the mapping never asks beyond it",
                            excess > 1e-9 ? describe_face(m, tidy(m, set, obj, worst->at)) : ""});
  }
  check_capability(cfg, out.findings);
  check_directions(cfg, set, out.findings);
  // Bus schedules against their frame budgets (the drivers' budget model).
  for (const BusBudgetResult& b : cfg.budgets) {
    using V = BusBudgetResult::Verdict;
    const Severity sev = b.verdict == V::kRefused   ? Severity::kFail
                         : b.verdict == V::kWarning ? Severity::kWarn
                                                    : Severity::kInfo;
    out.findings.push_back({sev, "bus budget", b.bus, b.text, ""});
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace facectl::verify
