#include "firmware-host/simulate/mapping_inverse.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "control/mapping/mandible_mechanism.hpp"

namespace facectl {

namespace {

// Levenberg–Marquardt damping, in the scaled variables' units (the Jacobian's columns are
// effector fractions per unit of a signal's span).
constexpr double kStartDamping = 1e-3, kMinDamping = 1e-12;
// Largest weighted residual of one actuator (a fraction of its effector span) above which
// a second start is tried: each position is meant to come back within 1e-4 of its range.
constexpr double kRestartResidual = 1e-4;

bool is_strut(const RigMapping& m, std::size_t actuator) {
  if (!m.mechanism) return false;
  for (std::size_t i = 0; i < m.mechanism->struts(); ++i) {
    if (m.mechanism->strut[i].actuator == actuator) return true;
  }
  return false;
}

bool is_jaw(const RigMapping& m, std::size_t signal) {
  return signal == m.jaw_pitch || signal == m.jaw_yaw || signal == m.jaw_protrusion;
}

// The effector value that makes the channel put the actuator at `position`:
// the transform inverted, positions beyond a curve's or linkage's ends taken
// at the end (the forward map holds them there too). nullopt where a linkage
// cannot close.
std::optional<double> effector_for(const ChannelTransform& t, double position) {
  switch (t.kind) {
    case ChannelTransform::Kind::kNone:
      return position;
    case ChannelTransform::Kind::kCalibration: {
      const double a = t.curve.y(0), b = t.curve.y(t.curve.size() - 1);
      return t.curve.inverse(std::clamp(position, std::min(a, b), std::max(a, b)));
    }
    case ChannelTransform::Kind::kLinkage: {
      const std::optional<double> e = t.linkage.to_effector(position);
      if (!e) return std::nullopt;
      return std::clamp(*e, t.linkage.effector_min, t.linkage.effector_max);
    }
  }
  return std::nullopt;
}

// How far the effector moves over the actuator's hardware range: the residual
// of an actuator counts in fractions of it, so that channels of different
// units weigh alike.
double effector_span(const ChannelTransform& t, const ActuatorLimits& limits) {
  const std::optional<double> lo = effector_for(t, limits.position_min);
  const std::optional<double> hi = effector_for(t, limits.position_max);
  double span = lo && hi ? std::fabs(*hi - *lo) : 0.0;
  if (!(span > 0.0) && t.kind == ChannelTransform::Kind::kLinkage) {
    span = t.linkage.effector_max - t.linkage.effector_min;
  }
  return std::isfinite(span) && span > 0.0 ? span : 1.0;
}

// Weighted effector residual of `face` into `r`; returns its squared norm.
double residual(const MappingInverse& inv, MappingInverseWorkspace& w,
                const std::array<double, kMaxFaceSignals>& face,
                MappingInverseWorkspace::Residual& r,
                const std::array<double, kMaxActuators>& weight) {
  const RigMapping& m = *inv.mapping;
  evaluate_control_points(m, w.mapping, face);
  map_effectors(m, w.mapping, face);
  for (std::size_t a = 0; a < m.actuators(); ++a) {
    r[static_cast<int>(a)] = weight[a] * (w.mapping.effector[a] - w.target[a]);
  }
  return r.squaredNorm();
}

double regulariser(const MappingInverse& inv, const std::array<double, kMaxFaceSignals>& face) {
  double sum = 0.0;
  for (std::size_t s = 0; s < inv.signals; ++s) {
    const double z = (face[s] - inv.neutral[s]) / inv.span[s];
    sum += z * z;
  }
  return inv.regularisation * sum;
}

// Jaw pose from the struts' positions (forward kinematics). Returns false and
// leaves the rest pose where it does not converge.
bool solve_jaw(const MappingInverse& inv, std::span<const double> positions,
               std::array<double, kMaxFaceSignals>& face) {
  const RigMapping& m = *inv.mapping;
  const MandibleMechanism& mech = *m.mechanism;
  MandibleStrokes strokes{};
  for (std::size_t i = 0; i < mech.struts(); ++i) strokes[i] = positions[mech.strut[i].actuator];
  const std::optional<face::MandiblePose> pose = forward(mech, strokes, inv.mandible_rest);
  const face::MandiblePose p = pose ? *pose : inv.mandible_rest;
  face[m.jaw_pitch] = p.pitch_rad;
  face[m.jaw_yaw] = p.yaw_rad;
  face[m.jaw_protrusion] = p.protrusion_m;
  return pose.has_value();
}

}  // namespace

MappingInverse make_mapping_inverse(const ControllerModel& model) {
  MappingInverse inv;
  const RigMapping& m = model.mapping;
  inv.mapping = &m;
  inv.signals = model.layout.size();
  inv.neutral = model.neutral;
  inv.mandible_rest = model.mandible_rest;
  for (std::size_t s = 0; s < inv.signals; ++s) {
    Range r = model.admissible[s];
    if (s == m.jaw_pitch) r = model.envelope.pitch;
    if (s == m.jaw_yaw) r = model.envelope.yaw;
    if (s == m.jaw_protrusion) r = model.envelope.protrusion;
    inv.lower[s] = r.min;
    inv.upper[s] = r.max;
    inv.span[s] = r.max > r.min ? r.max - r.min : 1.0;
  }
  const bool reads_points = std::any_of(m.points.begin(), m.points.end(),
                                        [](const PointTerm& p) { return p.gain != 0.0; });
  for (std::size_t a = 0; a < m.actuators(); ++a) {
    if (is_strut(m, a) || !m.drives(a)) continue;
    inv.weight[a] = 1.0 / effector_span(m.transforms[a], model.actuators[a].limits);
    for (std::size_t s = 0; s < inv.signals; ++s) {
      if (m.linear.gain(a, s) != 0.0) inv.observed[s] = true;
    }
  }
  for (std::size_t s = 0; s < inv.signals; ++s) {
    const bool model_input =
        s < m.muscle_count || is_jaw(m, s) || s == m.eyelid_closure[0] || s == m.eyelid_closure[1];
    if (reads_points && model_input) inv.observed[s] = true;
    if (m.mechanism && is_jaw(m, s)) inv.observed[s] = false;  // solved by forward kinematics
  }
  return inv;
}

MappingInverseWorkspace make_mapping_inverse_workspace(const MappingInverse& inverse) {
  MappingInverseWorkspace w;
  w.mapping = make_mapping_workspace(*inverse.mapping);
  const int actuators = static_cast<int>(inverse.mapping->actuators());
  w.residual.setZero(actuators);
  w.residual_trial.setZero(actuators);
  return w;
}

namespace {

// Levenberg–Marquardt from w.face over the n variables w.variable names; leaves the
// result in w.face and returns {cost, iterations}.
std::pair<double, int> descend(const MappingInverse& inv, MappingInverseWorkspace& w,
                               const std::array<double, kMaxActuators>& weight, int n) {
  const RigMapping& m = *inv.mapping;
  const int rows = static_cast<int>(m.actuators());
  double cost = residual(inv, w, w.face, w.residual, weight) + regulariser(inv, w.face);
  double damping = kStartDamping;

  int iterations = 0;
  for (int it = 0; it < MappingInverse::kMaxIterations && n > 0; ++it) {
    iterations = it + 1;
    // Jacobian in scaled variables u_s = x_s / span_s, by central differences.
    w.jacobian.setZero(rows, n);
    for (int k = 0; k < n; ++k) {
      const std::size_t s = static_cast<std::size_t>(w.variable[static_cast<std::size_t>(k)]);
      const double h = 1e-6 * inv.span[s];
      w.trial = w.face;
      w.trial[s] = w.face[s] + h;
      residual(inv, w, w.trial, w.residual_trial, weight);
      w.jacobian.col(k) = w.residual_trial;
      w.trial[s] = w.face[s] - h;
      residual(inv, w, w.trial, w.residual_trial, weight);
      w.jacobian.col(k) -= w.residual_trial;
      w.jacobian.col(k) *= inv.span[s] / (2.0 * h);
    }
    residual(inv, w, w.face, w.residual, weight);
    // Gradient; variables held at a bound by it leave the step (projected Gauss–Newton).
    w.gradient.noalias() = w.jacobian.transpose() * w.residual.head(rows);
    int free = 0;
    for (int k = 0; k < n; ++k) {
      const std::size_t s = static_cast<std::size_t>(w.variable[static_cast<std::size_t>(k)]);
      const double g =
          w.gradient[k] + inv.regularisation * (w.face[s] - inv.neutral[s]) / inv.span[s];
      const bool at_lower = w.face[s] <= inv.lower[s] && g > 0.0;
      const bool at_upper = w.face[s] >= inv.upper[s] && g < 0.0;
      w.gradient[k] = at_lower || at_upper ? 0.0 : g;
      if (!at_lower && !at_upper) ++free;
    }
    if (free == 0 || w.gradient.head(n).lpNorm<Eigen::Infinity>() < 1e-15) break;

    // Levenberg–Marquardt step on the free variables, clamped into the box: the damping
    // falls after a step that lowers the cost and rises until one does, so a step the
    // quadratic model misjudges turns toward the gradient rather than only shrinking
    // along a Gauss–Newton direction that leads into a bound.
    w.normal.noalias() = w.jacobian.transpose() * w.jacobian;
    w.normal.diagonal().array() += inv.regularisation;
    for (int k = 0; k < n; ++k) {
      if (w.gradient[k] != 0.0) continue;  // held at its bound: decouple it
      w.normal.row(k).setZero();
      w.normal.col(k).setZero();
      w.normal(k, k) = 1.0;
    }
    bool accepted = false;
    for (int attempt = 0; attempt < 30 && !accepted; ++attempt) {
      w.damped = w.normal;
      w.damped.diagonal().array() += damping;
      w.step = w.damped.ldlt().solve(-w.gradient.head(n));
      w.trial = w.face;
      for (int k = 0; k < n; ++k) {
        const std::size_t s = static_cast<std::size_t>(w.variable[static_cast<std::size_t>(k)]);
        w.trial[s] = std::clamp(w.face[s] + w.step[k] * inv.span[s], inv.lower[s], inv.upper[s]);
      }
      const double trial_cost =
          residual(inv, w, w.trial, w.residual_trial, weight) + regulariser(inv, w.trial);
      if (trial_cost < cost) {
        accepted = true;
        cost = trial_cost;
        w.face = w.trial;
        damping = std::max(damping / 3.0, kMinDamping);
      } else {
        damping *= 4.0;
      }
    }
    if (!accepted || w.step.head(n).lpNorm<Eigen::Infinity>() < 1e-12) break;
  }

  return {cost, iterations};
}

}  // namespace

bool needs_second_start(std::span<const double> weighted_residual) {
  return std::any_of(weighted_residual.begin(), weighted_residual.end(),
                     [](double r) { return std::fabs(r) > kRestartResidual; });
}

MappingInverseResult invert_mapping(const MappingInverse& inv, MappingInverseWorkspace& w,
                                    std::span<const double> positions,
                                    std::array<double, kMaxFaceSignals>& face) {
  const RigMapping& m = *inv.mapping;
  MappingInverseResult result;
  std::array<double, kMaxActuators> weight = inv.weight;
  for (std::size_t a = 0; a < m.actuators(); ++a) {
    if (weight[a] == 0.0) continue;
    const std::optional<double> e = effector_for(m.transforms[a], positions[a]);
    if (e && std::isfinite(*e)) {
      w.target[a] = *e;
    } else {
      weight[a] = 0.0;  // a linkage that cannot close tells nothing
    }
  }

  std::copy_n(inv.neutral.begin(), inv.signals, w.face.begin());
  if (m.mechanism) result.mandible_solved = solve_jaw(inv, positions, w.face);

  int n = 0;
  for (std::size_t s = 0; s < inv.signals; ++s) {
    if (inv.observed[s]) w.variable[static_cast<std::size_t>(n++)] = static_cast<int>(s);
  }
  const auto [cost, iterations] = descend(inv, w, weight, n);
  result.iterations = iterations;
  // A bound-constrained least squares over cubic features has local minima: where the
  // descent from neutral leaves a visible misfit, start again from the middle of the box.
  residual(inv, w, w.face, w.residual, weight);
  const int rows = static_cast<int>(m.actuators());
  if (inv.second_start && needs_second_start({w.residual.data(), static_cast<std::size_t>(rows)})) {
    w.best = w.face;
    for (int k = 0; k < n; ++k) {
      const std::size_t s = static_cast<std::size_t>(w.variable[static_cast<std::size_t>(k)]);
      w.face[s] = 0.5 * (inv.lower[s] + inv.upper[s]);
    }
    const auto [cost_again, iterations_again] = descend(inv, w, weight, n);
    result.iterations += iterations_again;
    if (!(cost_again < cost)) w.face = w.best;
  }

  const double fit = residual(inv, w, w.face, w.residual, weight);
  int used = 0;
  for (std::size_t a = 0; a < m.actuators(); ++a) used += weight[a] != 0.0;
  result.residual = used > 0 ? std::sqrt(fit / used) : 0.0;
  std::copy_n(w.face.begin(), inv.signals, face.begin());
  return result;
}

}  // namespace facectl
