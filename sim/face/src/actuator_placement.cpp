#include "facectl/face/actuator_placement.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

constexpr double kMm = 1000;

void report(const PlacementProgress& progress, const std::string& what) {
  if (progress) progress(what);
}

// Runs from the settled neutral state to a steady state under `in`, with `pins` held.
Points settle(const FaceModel& m, const PlacementProblem& p, FaceData& d, const FaceInput& in,
              bool& settled) {
  d = p.settled;  // same sizes: copies without allocating, pins included
  settled = run_to_steady_state(m, d, in, p.steady).converged;
  return d.skin_x;
}

// Displacement from the rest skin at the moving vertices, stacked as PlacementProblem rows.
Eigen::VectorXd stacked(const PlacementProblem& p, const Points& x) {
  Eigen::VectorXd v(3 * static_cast<Eigen::Index>(p.moving.size()));
  for (std::size_t i = 0; i < p.moving.size(); ++i) {
    const auto j = static_cast<std::size_t>(p.moving[i]);
    v.segment<3>(3 * static_cast<Eigen::Index>(i)) = x.get(j) - p.rest.get(j);
  }
  return v;
}

// Farthest-point sampling over `pool` (rest positions), seeded with `seed`: spread out.
std::vector<int> farthest_points(const Points& x, const std::vector<int>& pool, int seed,
                                 std::size_t n) {
  std::vector<int> out{seed};
  std::vector<double> gap(pool.size(), std::numeric_limits<double>::infinity());
  while (out.size() < std::min(n, pool.size())) {
    const Vec3 last = x.get(static_cast<std::size_t>(out.back()));
    std::size_t best = 0;
    for (std::size_t i = 0; i < pool.size(); ++i) {
      gap[i] = std::min(gap[i], (x.get(static_cast<std::size_t>(pool[i])) - last).norm());
      if (gap[i] > gap[best]) best = i;
    }
    if (gap[best] == 0) break;
    out.push_back(pool[best]);
  }
  return out;
}

// Principal directions of one vertex's target displacements across the library, largest
// first, dropping those carrying under 1% of the largest's energy.
std::vector<Vec3> principal_directions(const Eigen::MatrixXd& target, std::size_t row, int n) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (Eigen::Index e = 0; e < target.cols(); ++e) {
    const Vec3 u = target.block<3, 1>(static_cast<Eigen::Index>(3 * row), e);
    c += u * u.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c);
  std::vector<Vec3> out;
  for (int k = 2; k >= 0 && static_cast<int>(out.size()) < n; --k)
    if (eig.eigenvalues()[k] > 0.01 * eig.eigenvalues()[2] && eig.eigenvalues()[2] > 0)
      out.push_back(eig.eigenvectors().col(k).normalized());
  return out;
}

// Orthogonal matching pursuit with one shared column set for every expression: each step
// takes the candidate whose part orthogonal to the chosen ones removes the most residual
// energy summed over the expressions. One actuator per vertex.
std::vector<int> greedy_select(const PlacementProblem& p, int budget) {
  const Eigen::Index rows = p.response.rows();
  Eigen::MatrixXd residual = p.target;
  Eigen::MatrixXd q(rows, 0);
  std::vector<int> chosen;
  std::vector<char> vertex_used(p.rest.size(), 0);
  while (static_cast<int>(chosen.size()) < budget) {
    int best = -1;
    double best_gain = 0;
    for (Eigen::Index k = 0; k < p.response.cols(); ++k) {
      if (vertex_used[static_cast<std::size_t>(p.candidate_vertex[static_cast<std::size_t>(k)])])
        continue;
      Eigen::VectorXd u = p.response.col(k);
      const double full = u.norm();
      if (q.cols() > 0) u -= q * (q.transpose() * u);
      const double n = u.norm();
      if (n <= 1e-6 * full || full == 0) continue;  // already spanned
      const double gain = (residual.transpose() * u).squaredNorm() / (n * n);
      if (gain > best_gain) {
        best_gain = gain;
        best = static_cast<int>(k);
      }
    }
    if (best < 0) break;
    Eigen::VectorXd u = p.response.col(best);
    for (int pass = 0; pass < 2; ++pass)  // twice: Gram–Schmidt loses orthogonality once
      if (q.cols() > 0) u -= q * (q.transpose() * u);
    u.normalize();
    residual -= u * (u.transpose() * residual);
    q.conservativeResize(Eigen::NoChange, q.cols() + 1);
    q.col(q.cols() - 1) = u;
    chosen.push_back(best);
    vertex_used[static_cast<std::size_t>(p.candidate_vertex[static_cast<std::size_t>(best)])] = 1;
  }
  return chosen;
}

void set_pins(FaceData& d, const std::vector<int>& vertex, const std::vector<Vec3>& target) {
  clear_skin_pins(d.pins);
  for (std::size_t k = 0; k < vertex.size(); ++k) add_skin_pin(d.pins, vertex[k], target[k]);
}

// Returns the vertex of the max.
int errors_mm(const PlacementProblem& p, const Points& x, const Points& goal, double& rms,
              double& max) {
  double sum = 0;
  max = 0;
  int worst = -1;
  for (int v : p.moving) {
    const auto j = static_cast<std::size_t>(v);
    const double e = (x.get(j) - goal.get(j)).norm() * kMm;
    sum += e * e;
    if (e > max) {
      max = e;
      worst = v;
    }
  }
  rms = p.moving.empty() ? 0 : std::sqrt(sum / static_cast<double>(p.moving.size()));
  return worst;
}

// The library's expressions to reproduce: all, or those named, each once.
std::vector<Expression> chosen_expressions(const ExpressionLibrary& lib,
                                           const std::vector<std::string>& names) {
  if (names.empty()) return lib.expressions;
  std::vector<Expression> out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const Expression* e = lib.find(names[i]);
    if (!e) throw InputError("expected an expression of the library, found '" + names[i] + "'");
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) !=
        names.begin() + static_cast<std::ptrdiff_t>(i))
      throw InputError("expression '" + names[i] + "' is named twice");
    out.push_back(*e);
  }
  return out;
}

// 1. Targets: each expression at steady state, and its jaw and lids alone.
void settle_targets(const FaceModel& m, PlacementProblem& p, const PlacementProgress& progress) {
  FaceData d = p.settled;
  bool ok = true;
  for (const Expression& e : p.expressions) {
    report(progress, "target " + e.name);
    p.full.push_back(settle(m, p, d, face_input(e), ok));
    p.unsettled += !ok;
    p.jaw_only.push_back(settle(m, p, d, jaw_and_lids_input(m, e), ok));
    p.unsettled += !ok;
    p.runs += 2;
  }
}

// How far each vertex moves over the library: in all (moved) and in its soft tissue alone
// (soft, the part the jaw and lids do not carry); row_of[v]: v's row block, or −1.
struct Motion {
  std::vector<double> moved, soft;
  std::vector<int> row_of;
};

// The vertices that move more than `threshold_mm` in some expression, and the targets on them.
Motion choose_moving_vertices(PlacementProblem& p, double threshold_mm) {
  const std::size_t nv = p.rest.size();
  Motion mo{std::vector<double>(nv, 0), std::vector<double>(nv, 0), std::vector<int>(nv, -1)};
  for (std::size_t e = 0; e < p.expressions.size(); ++e)
    for (std::size_t i = 0; i < nv; ++i) {
      mo.moved[i] = std::max(mo.moved[i], (p.full[e].get(i) - p.rest.get(i)).norm() * kMm);
      mo.soft[i] = std::max(mo.soft[i], (p.full[e].get(i) - p.jaw_only[e].get(i)).norm() * kMm);
    }
  for (std::size_t i = 0; i < nv; ++i)
    if (mo.moved[i] > threshold_mm) {
      mo.row_of[i] = static_cast<int>(p.moving.size());
      p.moving.push_back(static_cast<int>(i));
    }
  p.target.resize(3 * static_cast<Eigen::Index>(p.moving.size()),
                  static_cast<Eigen::Index>(p.expressions.size()));
  for (std::size_t e = 0; e < p.expressions.size(); ++e)
    p.target.col(static_cast<Eigen::Index>(e)) = stacked(p, p.full[e]) - stacked(p, p.jaw_only[e]);
  return mo;
}

// 2. Candidates: spread-out vertices whose soft tissue moves, along their principal
// directions.
void choose_candidates(PlacementProblem& p, const PlacementOptions& o, const Motion& mo) {
  std::vector<int> pool;
  int seed = -1;
  for (int v : p.moving) {
    const double soft = mo.soft[static_cast<std::size_t>(v)];
    if (soft <= o.moving_threshold_mm) continue;
    pool.push_back(v);
    if (seed < 0 || soft > mo.soft[static_cast<std::size_t>(seed)]) seed = v;
  }
  if (pool.empty()) return;
  const std::vector<int> picked = farthest_points(
      p.rest, pool, seed, static_cast<std::size_t>(std::max(1, o.max_candidate_vertices)));
  for (int v : picked)
    for (const Vec3& a : principal_directions(
             p.target, static_cast<std::size_t>(mo.row_of[static_cast<std::size_t>(v)]),
             o.directions)) {
      p.candidate_vertex.push_back(v);
      p.candidate_axis.push_back(a);
    }
}

// 3. Responses: each candidate alone pinned one step along its axis, muscles relaxed.
void measure_responses(const FaceModel& m, PlacementProblem& p, const PlacementProgress& progress) {
  p.response.resize(p.target.rows(), static_cast<Eigen::Index>(p.candidate_vertex.size()));
  FaceData d = p.settled;
  for (std::size_t k = 0; k < p.candidate_vertex.size(); ++k) {
    if (k % 50 == 0)
      report(progress,
             "responses " + std::to_string(k) + "/" + std::to_string(p.candidate_vertex.size()));
    const auto v = static_cast<std::size_t>(p.candidate_vertex[k]);
    d = p.settled;
    set_pins(d, {p.candidate_vertex[k]}, {p.rest.get(v) + p.step_m * p.candidate_axis[k]});
    p.unsettled += !run_to_steady_state(m, d, FaceInput{}, p.steady).converged;
    ++p.runs;
    p.response.col(static_cast<Eigen::Index>(k)) = stacked(p, d.skin_x);
  }
}

// The chosen actuators: each one's vertex and axis.
struct Chosen {
  std::vector<int> vertex;
  std::vector<Vec3> axis;
};

// Joint responses: actuator k one step along its axis with the others held at rest. The
// single-point responses guided the choice, but with every point held the field is a
// combination of these, which the travels are fitted in.
Eigen::MatrixXd joint_responses(const FaceModel& m, const PlacementProblem& p, const Chosen& c,
                                const PlacementProgress& progress, int& unsettled) {
  const std::size_t n = c.vertex.size();
  Eigen::MatrixXd joint(p.target.rows(), static_cast<Eigen::Index>(n));
  FaceData d = p.settled;
  std::vector<Vec3> pin(n);
  for (std::size_t k = 0; k < n; ++k) {
    report(progress, "joint response " + std::to_string(k + 1) + "/" + std::to_string(n));
    for (std::size_t j = 0; j < n; ++j)
      pin[j] =
          p.rest.get(static_cast<std::size_t>(c.vertex[j])) + (j == k ? p.step_m : 0) * c.axis[j];
    d = p.settled;
    set_pins(d, c.vertex, pin);
    unsettled += !run_to_steady_state(m, d, FaceInput{}, p.steady).converged;
    joint.col(static_cast<Eigen::Index>(k)) = stacked(p, d.skin_x);
  }
  return joint;
}

// Validation of expression e on the full model: the jaw and lids as the expression has
// them, each point where the jaw alone carries it plus its actuator's travel (`steps`).
ExpressionFit validate(const FaceModel& m, const PlacementProblem& p, const Chosen& c,
                       std::size_t e, const Eigen::VectorXd& steps) {
  const std::size_t n = c.vertex.size();
  ExpressionFit f;
  f.name = p.expressions[e].name;
  f.worst_vertex = errors_mm(p, p.jaw_only[e], p.full[e], f.rms0_mm, f.max0_mm);
  std::vector<Vec3> pin(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double s = steps(static_cast<Eigen::Index>(k));
    f.travel_mm.push_back(s * p.step_m * kMm);
    pin[k] = p.jaw_only[e].get(static_cast<std::size_t>(c.vertex[k])) + s * p.step_m * c.axis[k];
  }
  if (n == 0) {
    f.rms_mm = f.rms0_mm;
    f.max_mm = f.max0_mm;
    return f;
  }
  FaceData d = p.settled;
  set_pins(d, c.vertex, pin);
  f.settled =
      run_to_steady_state(m, d, jaw_and_lids_input(m, p.expressions[e]), p.steady).converged;
  f.worst_vertex = errors_mm(p, d.skin_x, p.full[e], f.rms_mm, f.max_mm);
  return f;
}

// Actuator k as a rig would take it: where it is, its nearest control point, its travels.
PlacedActuator describe(const FaceModel& m, const PlacementProblem& p, const Chosen& c,
                        const std::vector<ExpressionFit>& fits, std::size_t k) {
  PlacedActuator a;
  a.vertex = c.vertex[k];
  a.axis = c.axis[k];
  const auto v = static_cast<std::size_t>(a.vertex);
  a.position_mm = p.rest.get(v) * kMm;
  for (const LandmarkSpec& l : m.spec.landmarks)
    if (l.vertices.size() == 1 && l.vertices[0] == a.vertex && l.offset.isZero())
      a.landmark = l.name;
  a.control_point_distance_mm = std::numeric_limits<double>::infinity();
  for (const std::string& name : m.spec.control_points) {
    const int li = m.landmark_index(name);
    if (li < 0) continue;
    const double dist = (landmark_position(m, p.rest, li) - p.rest.get(v)).norm() * kMm;
    if (dist < a.control_point_distance_mm) {
      a.control_point_distance_mm = dist;
      a.nearest_control_point = name;
    }
  }
  if (a.nearest_control_point.empty()) a.control_point_distance_mm = 0;
  for (const ExpressionFit& f : fits) {
    a.travel_min_mm = std::min(a.travel_min_mm, f.travel_mm[k]);
    a.travel_max_mm = std::max(a.travel_max_mm, f.travel_mm[k]);
  }
  return a;
}

}  // namespace

FaceInput jaw_and_lids_input(const FaceModel& m, const Expression& e) {
  const FaceInput full = face_input(e);
  FaceInput in;
  in.jaw = e.jaw;
  for (int s = 0; s < 2; ++s) in.eyelid_closure[s] = lid_closure(m, full, s);
  return in;
}

PlacementProblem build_placement_problem(const FaceModel& m, const ExpressionLibrary& lib,
                                         const PlacementOptions& o,
                                         const PlacementProgress& progress) {
  PlacementProblem p;
  p.step_m = o.step_mm / kMm;
  p.steady = o.steady;
  p.expressions = chosen_expressions(lib, o.expressions);
  p.settled = make_face_data(m);
  reset_face_data(m, p.settled);
  run_to_steady_state(m, p.settled, FaceInput{}, p.steady);
  reserve_skin_pins(p.settled.pins, m.skin.v.size(), m.skin.v.size());
  p.rest = p.settled.skin_x;
  settle_targets(m, p, progress);
  const Motion motion = choose_moving_vertices(p, o.moving_threshold_mm);
  choose_candidates(p, o, motion);
  measure_responses(m, p, progress);
  return p;
}

Placement place_actuators(const FaceModel& m, const PlacementProblem& p, int budget,
                          const PlacementProgress& progress) {
  Placement out;
  const std::vector<int> chosen = greedy_select(p, std::max(0, budget));
  Chosen c;
  for (int k : chosen) {
    c.vertex.push_back(p.candidate_vertex[static_cast<std::size_t>(k)]);
    c.axis.push_back(p.candidate_axis[static_cast<std::size_t>(k)]);
  }
  const std::size_t n = chosen.size();
  const Eigen::MatrixXd joint = joint_responses(m, p, c, progress, out.unsettled);
  // Steps of each actuator per expression, least squares in the joint responses.
  const Eigen::MatrixXd steps = n > 0 ? Eigen::MatrixXd(joint.colPivHouseholderQr().solve(p.target))
                                      : Eigen::MatrixXd(0, p.target.cols());
  for (std::size_t e = 0; e < p.expressions.size(); ++e) {
    report(progress, "validate " + p.expressions[e].name);
    out.fits.push_back(validate(m, p, c, e, steps.col(static_cast<Eigen::Index>(e))));
    out.unsettled += !out.fits.back().settled;
  }
  for (std::size_t k = 0; k < n; ++k) out.actuators.push_back(describe(m, p, c, out.fits, k));
  return out;
}

}  // namespace facectl::face
