#include "control/mapping/mandible_mechanism.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "control/units.hpp"

namespace facectl {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// The nearest-reachable clamp: at most kSolveIterations Gauss–Newton steps, each
// halved at most kHalvings − 1 times, each trial pose found by at most
// kNewtonIterations Newton steps. It stops early at a step shorter than
// kStepTolerance metric units (1e-9 mm or degree by default).
constexpr int kSolveIterations = 10;
constexpr int kHalvings = 4;
constexpr int kNewtonIterations = 6;
constexpr double kStepTolerance = 1e-9;
// Slack, in m (stroke) or rad, within which a QP candidate counts as feasible.
constexpr double kFeasibleSlack = 1e-12;

bool finite(const Vector3d& v) {
  return v.allFinite();
}

// The pitch and yaw rotations of a pose are built once per pose and shared by every
// strut, because their sines cost more than a strut's own arithmetic.
using Motion = MandibleRotations;

// Whether a rotation built for `built` serves `angle`: the same bits (sin(−0) is
// −0; a NaN never serves).
bool same_angle(double built, double angle) {
  return built == angle && std::signbit(built) == std::signbit(angle);
}

// `r` updated to the rotations of q.
void rotate_to(const face::MandibleAxes& a, const MandibleVector& q, Motion& r) {
  if (!same_angle(r.pitch_rad, q[0])) {
    r.pitch = face::rodrigues(a.pitch_axis, q[0]);
    r.pitch_rad = q[0];
  }
  if (!same_angle(r.yaw_rad, q[1])) {
    r.yaw = face::rodrigues(a.yaw_axis, q[1]);
    r.yaw_rad = q[1];
  }
}

// A mandible anchor moved by the pose (pitch, then yaw, then protrusion), with the
// intermediate points the Jacobian needs.
struct Moved {
  Vector3d r;  // pitched, relative to the pitch point
  Vector3d w;  // pitched and yawed, relative to the yaw point
  Vector3d p;  // the moved anchor, head frame
};

Moved move(const face::MandibleAxes& a, const Motion& mo, const Vector3d& arm, double protrusion) {
  Moved m;
  m.r = mo.pitch * arm;
  m.w = mo.yaw * (m.r + a.pitch_point - a.yaw_point);
  m.p = m.w + a.yaw_point + protrusion * a.protrusion_dir;
  return m;
}

// Strokes at q (held DOFs applied), and with `jacobian` also d stroke_i / d q_k;
// with `rotations`, reusing and keeping them.
void evaluate(const MandibleMechanism& m, const MandibleVector& q, MandibleStrokes& out,
              Matrix3d* jacobian, Motion* rotations = nullptr) {
  const face::MandibleAxes& a = m.axes;
  Motion local;
  Motion& mo = rotations != nullptr ? *rotations : local;
  rotate_to(a, q, mo);
  for (std::size_t i = 0; i < m.count; ++i) {
    const MandibleStrut& s = m.strut[i];
    const Moved mv = move(a, mo, m.arm[i], q[2]);
    const Vector3d d = mv.p - s.skull;
    const double L = d.norm();
    out[i] = s.stroke_at_rest + L - m.rest_length[i];
    if (jacobian == nullptr) continue;
    const Vector3d e = d / L;  // unit, skull → mandible
    (*jacobian)(i, 0) = e.dot(mo.yaw * a.pitch_axis.cross(mv.r));
    (*jacobian)(i, 1) = e.dot(a.yaw_axis.cross(mv.w));
    (*jacobian)(i, 2) = e.dot(a.protrusion_dir);
  }
  if (jacobian == nullptr) return;
  for (std::size_t i = m.count; i < 3; ++i) jacobian->row(i).setZero();
}

// Rows i < count: d stroke_i / dq (only the driven columns are used). Rows for the
// DOFs that are not driven are unit rows, so the square system also pins them;
// `aug` lists, per row, the strut (< count) or the pinned DOF (>= count: count + dof).
struct Augmented {
  Matrix3d J;
  Vector3d value;  // strokes, then the pinned DOFs' values
  Vector3d lo, hi;
};

// From the strokes `s` and their Jacobian `full` at q.
Augmented augmented(const MandibleMechanism& m, const MandibleVector& q, const MandibleStrokes& s,
                    const Matrix3d& full) {
  Augmented a;
  std::size_t row = 0;
  for (std::size_t i = 0; i < m.count; ++i, ++row) {
    a.J.row(row).setZero();
    for (std::size_t k = 0; k < 3; ++k)
      if (m.driven[k]) a.J(row, k) = full(i, k);
    a.value[row] = s[i];
    a.lo[row] = m.strut[i].stroke.min;
    a.hi[row] = m.strut[i].stroke.max;
  }
  const MandibleVector held = to_vector(m.held);
  for (std::size_t k = 0; k < 3; ++k) {
    if (m.driven[k]) continue;
    a.J.row(row).setZero();
    a.J(row, k) = 1.0;
    a.value[row] = q[k];
    a.lo[row] = a.hi[row] = held[k];
    ++row;
  }
  return a;
}

bool invert(const Matrix3d& J, Matrix3d& inverse) {
  bool ok = false;
  double det = 0.0;
  const double scale = J.row(0).norm() * J.row(1).norm() * J.row(2).norm();
  J.computeInverseAndDetWithCheck(inverse, det, ok, 1e-12 * scale);
  return ok && std::isfinite(det) && inverse.allFinite();
}

// min yᵀHy − 2gᵀy  s.t. lo <= y <= hi (H symmetric positive definite, 3×3), solved
// exactly by enumerating the 27 active sets (each variable free, at lo, or at hi)
// in order of the number of active bounds, and stopping at the first that
// satisfies the KKT conditions. The best feasible candidate is the fallback.
Vector3d box_qp(const Matrix3d& H, const Vector3d& g, const Vector3d& lo, const Vector3d& hi) {
  // Every variable at its lower bound is always feasible: the fallback of last resort.
  Vector3d best = lo;
  double best_f = std::numeric_limits<double>::infinity();
  const double grad_slack =
      1e-9 * (H.norm() * (lo.cwiseAbs() + hi.cwiseAbs()).maxCoeff() + g.norm());
  for (int active = 0; active <= 3; ++active) {
    for (int code = 0; code < 27; ++code) {
      int state[3] = {code % 3, (code / 3) % 3, code / 9};  // 0 free, 1 at lo, 2 at hi
      int n_active = 0;
      bool duplicate = false;
      for (int i = 0; i < 3; ++i) {
        if (state[i] != 0) ++n_active;
        if (state[i] == 2 && lo[i] == hi[i]) duplicate = true;
      }
      if (n_active != active || duplicate) continue;
      Matrix3d M = H;
      Vector3d rhs = g;
      for (int i = 0; i < 3; ++i) {
        if (state[i] == 0) continue;
        M.row(i).setZero();
        M(i, i) = 1.0;
        rhs[i] = state[i] == 1 ? lo[i] : hi[i];
      }
      Matrix3d Minv;
      if (!invert(M, Minv)) continue;
      Vector3d y = Minv * rhs;
      bool feasible = y.allFinite();
      for (int i = 0; i < 3 && feasible; ++i)
        feasible = y[i] >= lo[i] - kFeasibleSlack && y[i] <= hi[i] + kFeasibleSlack;
      if (!feasible) continue;
      y = y.cwiseMax(lo).cwiseMin(hi);
      const double f = y.dot(H * y) - 2.0 * g.dot(y);
      // KKT: the gradient pushes an active variable against its bound.
      const Vector3d grad = H * y - g;
      bool kkt = true;
      for (int i = 0; i < 3; ++i) {
        if (state[i] == 1 && lo[i] != hi[i] && grad[i] < -grad_slack) kkt = false;
        if (state[i] == 2 && grad[i] > grad_slack) kkt = false;
      }
      if (kkt) return y;
      if (f < best_f) {
        best_f = f;
        best = y;
      }
    }
  }
  return best;
}

double metric_distance(const MandibleMechanism& m, const MandibleVector& a,
                       const MandibleVector& b) {
  double d2 = 0.0;
  for (std::size_t k = 0; k < 3; ++k)
    if (m.driven[k]) d2 += std::pow(m.weight[k] * (a[k] - b[k]), 2);
  return std::sqrt(d2);
}

void clip_strokes(const MandibleMechanism& m, MandibleStrokes& s) {
  for (std::size_t i = 0; i < m.count; ++i)
    s[i] = std::clamp(s[i], m.strut[i].stroke.min, m.strut[i].stroke.max);
}

// Newton on strokes(x) = target from at.pose (updated in place; held DOFs stay
// held). True once every residual is at most `tolerance`. Each step evaluates
// the strokes with their Jacobian once, so `at` ends linearised at its pose: the
// next solve from there (the tick's, warm-started) needs no evaluation to start.
bool newton(const MandibleMechanism& m, const MandibleStrokes& target, MandibleLinearisation& at,
            int max_iterations, double tolerance = kForwardTolerance) {
  const auto converged = [&](const MandibleStrokes& s) {
    for (std::size_t i = 0; i < m.count; ++i) {
      if (!(std::fabs(s[i] - target[i]) <= tolerance)) return false;  // a NaN is not converged
    }
    return true;
  };
  MandibleVector& x = at.pose;
  for (int it = 0; it <= max_iterations; ++it) {
    if (!at.evaluated) {
      strokes_and_jacobian(m, x, at.strokes, at.jacobian);
      at.evaluated = true;
    }
    if (it > 0) {
      if (converged(at.strokes)) return true;
      if (it == max_iterations) break;
    }
    const Augmented a = augmented(m, x, at.strokes, at.jacobian);
    Vector3d residual = Vector3d::Zero();
    for (std::size_t i = 0; i < m.count; ++i) residual[i] = a.value[i] - target[i];
    if (!residual.allFinite()) return false;
    if (residual.cwiseAbs().maxCoeff() <= tolerance) return true;
    if (it == max_iterations) break;
    Matrix3d Jinv;
    if (!invert(a.J, Jinv)) return false;
    x = m.held_in(x - Jinv * residual);
    at.evaluated = false;
  }
  return false;
}

// Newton from x (updated in place), evaluated from scratch.
bool newton(const MandibleMechanism& m, const MandibleStrokes& target, MandibleVector& x,
            int max_iterations) {
  MandibleLinearisation at(x);
  const bool ok = newton(m, target, at, max_iterations);
  x = at.pose;
  return ok;
}

[[noreturn]] void reject(const std::string& what) {
  throw std::invalid_argument("mandible mechanism: " + what);
}

std::string describe(const face::MandiblePose& p) {
  std::ostringstream o;
  o.precision(4);
  o << "pitch " << p.pitch_rad * kDegPerRad << " deg, yaw " << p.yaw_rad * kDegPerRad
    << " deg, protrusion " << p.protrusion_m * 1000.0 << " mm";
  return o.str();
}

}  // namespace

std::string_view to_string(MandibleDof dof) {
  switch (dof) {
    case MandibleDof::kPitch:
      return "pitch";
    case MandibleDof::kYaw:
      return "yaw";
    case MandibleDof::kProtrusion:
      return "protrusion";
  }
  return "?";
}

MandibleVector to_vector(const face::MandiblePose& p) {
  return {p.pitch_rad, p.yaw_rad, p.protrusion_m};
}

face::MandiblePose to_pose(const MandibleVector& q) {
  return {q[0], q[1], q[2]};
}

MandibleVector MandibleMechanism::held_in(const MandibleVector& q) const {
  const MandibleVector h = to_vector(held);
  MandibleVector out;
  for (std::size_t k = 0; k < 3; ++k) out[k] = driven[k] ? q[k] : h[k];
  return out;
}

Vector3d mandible_anchor(const MandibleMechanism& m, std::size_t i, const MandibleVector& q) {
  Motion mo;
  rotate_to(m.axes, q, mo);
  return move(m.axes, mo, m.arm[i], q[2]).p;
}

void strokes(const MandibleMechanism& m, const face::MandiblePose& pose, MandibleStrokes& out,
             MandibleRotations* rotations) {
  evaluate(m, m.held_in(to_vector(pose)), out, nullptr, rotations);
}

void strokes_and_jacobian(const MandibleMechanism& m, const MandibleVector& q, MandibleStrokes& out,
                          Matrix3d& jacobian) {
  evaluate(m, q, out, &jacobian);
}

MandibleSolveResult solve(const MandibleMechanism& m, const face::MandiblePose& target,
                          MandibleStrokes& out_strokes, MandibleRotations* rotations) {
  MandibleVector goal = to_vector(target);
  MandibleSolveResult result;
  if (!goal.allFinite()) {
    const MandibleVector rest = m.held_in(MandibleVector::Zero());
    strokes(m, to_pose(rest), out_strokes);
    clip_strokes(m, out_strokes);
    result.achieved = to_pose(rest);
    result.clamped = true;
    result.distance = std::numeric_limits<double>::infinity();
    return result;
  }
  goal = m.held_in(goal);
  strokes(m, to_pose(goal), out_strokes, rotations);
  bool inside = true;
  for (std::size_t i = 0; i < m.count; ++i)
    inside = inside && out_strokes[i] >= m.strut[i].stroke.min &&
             out_strokes[i] <= m.strut[i].stroke.max;
  result.achieved = to_pose(goal);
  if (inside) return result;

  // Nearest reachable: min |W(x − goal)|² s.t. lo <= strokes(x) <= hi, as projected
  // Gauss–Newton in stroke space. The iterate is a stroke vector y inside the box
  // and the pose x it produces (Newton). Each step linearises x(y) at y
  // (x' = x + J⁻¹·(y' − y)) and solves the QP in y' exactly, where the limits are
  // a box; a step that does not shorten the distance is halved, and one that
  // cannot be made to is not taken. So y never leaves the box, and x is always
  // the pose of y.
  const Matrix3d W = m.weight.asDiagonal();
  MandibleStrokes y = out_strokes;
  clip_strokes(m, y);
  MandibleVector x = goal;
  if (!newton(m, y, x, kNewtonIterations)) {  // start at rest instead: it is reachable
    x = m.held_in(MandibleVector::Zero());
    strokes(m, to_pose(x), y);
  }
  double f = (W * (x - goal)).squaredNorm();
  for (int it = 0; it < kSolveIterations; ++it) {
    MandibleStrokes s{};
    Matrix3d full;
    strokes_and_jacobian(m, x, s, full);
    Augmented a = augmented(m, x, s, full);
    for (std::size_t i = 0; i < m.count; ++i) a.value[i] = y[i];  // the box point itself
    Matrix3d Jinv;
    if (!invert(a.J, Jinv)) break;
    const Matrix3d A = W * Jinv;
    const Vector3d c = W * (goal - x) + A * a.value;
    const Vector3d dy = box_qp(A.transpose() * A, A.transpose() * c, a.lo, a.hi) - a.value;
    if (!dy.allFinite() || (A * dy).norm() < kStepTolerance) break;
    result.iterations = it + 1;
    bool accepted = false;
    double alpha = 1.0;
    for (int h = 0; h < kHalvings && !accepted; ++h, alpha *= 0.5) {
      MandibleStrokes y_try = y;
      for (std::size_t i = 0; i < m.count; ++i) y_try[i] = y[i] + alpha * dy[i];
      clip_strokes(m, y_try);  // a convex combination of box points, up to rounding
      MandibleVector x_try = m.held_in(x + alpha * (Jinv * dy));
      if (!newton(m, y_try, x_try, kNewtonIterations)) continue;
      const double f_try = (W * (x_try - goal)).squaredNorm();
      if (!(f_try < f)) continue;
      accepted = true;
      x = x_try;
      y = y_try;
      f = f_try;
    }
    if (!accepted) break;
  }
  out_strokes = y;
  result.achieved = to_pose(x);
  result.clamped = true;
  result.distance = metric_distance(m, x, goal);
  return result;
}

std::optional<face::MandiblePose> forward(const MandibleMechanism& m, const MandibleStrokes& target,
                                          const face::MandiblePose& guess, int max_iterations,
                                          double tolerance) {
  MandibleLinearisation at(m.held_in(to_vector(guess)));
  return forward(m, target, at, max_iterations, tolerance);
}

std::optional<face::MandiblePose> forward(const MandibleMechanism& m, const MandibleStrokes& target,
                                          MandibleLinearisation& warm, int max_iterations,
                                          double tolerance) {
  MandibleLinearisation at = warm;
  if (!at.evaluated) at.pose = m.held_in(at.pose);
  if (!at.pose.allFinite() || !newton(m, target, at, max_iterations, tolerance))
    return std::nullopt;
  warm = at;
  return to_pose(at.pose);
}

MandibleConditioning conditioning(const MandibleMechanism& m, const MandibleEnvelope& envelope,
                                  int samples) {
  MandibleConditioning out;
  out.smallest_singular = std::numeric_limits<double>::infinity();
  const std::array<Range, 3> range = {envelope.pitch, envelope.yaw, envelope.protrusion};
  const int n = std::max(samples, 2);
  std::array<int, 3> steps{};
  for (std::size_t k = 0; k < 3; ++k) steps[k] = m.driven[k] ? n : 1;
  const std::size_t dim = m.count;
  for (int i0 = 0; i0 < steps[0]; ++i0)
    for (int i1 = 0; i1 < steps[1]; ++i1)
      for (int i2 = 0; i2 < steps[2]; ++i2) {
        const std::array<int, 3> idx = {i0, i1, i2};
        MandibleVector q;
        for (std::size_t k = 0; k < 3; ++k)
          q[k] = steps[k] == 1 ? 0.0
                               : range[k].min + (range[k].max - range[k].min) * idx[k] /
                                                    static_cast<double>(steps[k] - 1);
        q = m.held_in(q);
        MandibleStrokes s{};
        Matrix3d J;
        strokes_and_jacobian(m, q, s, J);
        Eigen::MatrixXd Jw(dim, dim);  // stroke mm per metric unit
        for (std::size_t c = 0; c < dim; ++c) {
          const auto k = static_cast<std::size_t>(m.dof[c]);
          for (std::size_t r = 0; r < dim; ++r) Jw(r, c) = J(r, k) * 1000.0 / m.weight[k];
        }
        const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(Jw).singularValues();
        const double smin = sv[static_cast<Eigen::Index>(dim) - 1];
        const double cond = smin > 0.0 ? sv[0] / smin : std::numeric_limits<double>::infinity();
        if (!(cond <= out.worst_condition)) {
          out.worst_condition = cond;
          out.worst_pose = to_pose(q);
        }
        if (!(smin >= out.smallest_singular)) {
          out.smallest_singular = smin;
          out.smallest_pose = to_pose(q);
        }
      }
  return out;
}

MandibleMechanism make_mandible_mechanism(const face::MandibleAxes& axes,
                                          std::span<const MandibleDof> dofs,
                                          std::span<const MandibleStrut> struts,
                                          const MandibleEnvelope& envelope,
                                          const face::MandiblePose& held,
                                          const MandibleMetric& metric, double max_condition) {
  if (struts.size() < 2 || struts.size() > MandibleMechanism::kMaxStruts)
    reject("expected 2 or 3 struts, found " + std::to_string(struts.size()));
  if (dofs.size() != struts.size())
    reject("expected one driven DOF per strut (" + std::to_string(struts.size()) + "), found " +
           std::to_string(dofs.size()));
  for (const Vector3d* v : {&axes.pitch_point, &axes.yaw_point})
    if (!finite(*v)) reject("an axis point is not finite");
  for (const Vector3d* v : {&axes.pitch_axis, &axes.yaw_axis, &axes.protrusion_dir})
    if (!finite(*v) || std::fabs(v->norm() - 1.0) > 1e-9) reject("an axis is not a unit vector");
  if (!(metric.angle_per_rad > 0.0 && metric.length_per_m > 0.0 &&
        std::isfinite(metric.angle_per_rad) && std::isfinite(metric.length_per_m)))
    reject("the metric's scales must be positive and finite");
  if (!to_vector(held).allFinite()) reject("the held pose is not finite");

  MandibleMechanism m;
  m.axes = axes;
  m.held = held;
  m.metric = metric;
  m.count = struts.size();
  m.weight = {metric.angle_per_rad, metric.angle_per_rad, metric.length_per_m};
  for (std::size_t i = 0; i < m.count; ++i) {
    const auto k = static_cast<std::size_t>(dofs[i]);
    if (k > 2) reject("unknown DOF");
    if (m.driven[k]) reject("DOF " + std::string(to_string(dofs[i])) + " is driven twice");
    m.driven[k] = true;
    m.dof[i] = dofs[i];
    const MandibleStrut& s = struts[i];
    const std::string name =
        "strut " + std::to_string(i) + " (actuator " + std::to_string(s.actuator) + "): ";
    if (!finite(s.skull) || !finite(s.mandible) || !std::isfinite(s.stroke_at_rest) ||
        !std::isfinite(s.stroke.min) || !std::isfinite(s.stroke.max))
      reject(name + "a number is not finite");
    if (!(s.stroke.min < s.stroke.max))
      reject(name + "the stroke limits need min < max, found [" + std::to_string(s.stroke.min) +
             ", " + std::to_string(s.stroke.max) + "] m");
    m.rest_length[i] = (s.skull - s.mandible).norm();
    m.arm[i] = s.mandible - axes.pitch_point;
    if (m.rest_length[i] < 1e-3) reject(name + "the anchors are less than 1 mm apart");
    m.strut[i] = s;
  }
  // The fallback pose (driven DOFs at rest) must be reachable.
  MandibleStrokes rest{};
  strokes(m, to_pose(m.held_in(MandibleVector::Zero())), rest);
  for (std::size_t i = 0; i < m.count; ++i)
    if (rest[i] < m.strut[i].stroke.min || rest[i] > m.strut[i].stroke.max)
      reject("strut " + std::to_string(i) + " (actuator " + std::to_string(m.strut[i].actuator) +
             "): the rest pose needs a stroke of " + std::to_string(rest[i] * 1000.0) +
             " mm, outside its limits");
  for (const Range* r : {&envelope.pitch, &envelope.yaw, &envelope.protrusion})
    if (!(r->min <= r->max) || !std::isfinite(r->min) || !std::isfinite(r->max))
      reject("the envelope needs finite ranges with min <= max");
  const MandibleConditioning c = conditioning(m, envelope);
  if (!(c.worst_condition <= max_condition))
    reject("the Jacobian is ill-conditioned over the envelope: condition " +
           std::to_string(c.worst_condition) + " (at most " + std::to_string(max_condition) +
           ") at " + describe(c.worst_pose));
  return m;
}

}  // namespace facectl
