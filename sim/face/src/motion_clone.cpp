#include "facectl/face/motion_clone.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "control/envelope/mandible_envelope.hpp"
#include "control/units.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/steady_state.hpp"

namespace facectl::face {
namespace {

constexpr double kMmPerM = 1e3;

// Names in `a` that `b` lacks, comma-separated.
std::string missing(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  std::string out;
  for (const std::string& n : a)
    if (std::find(b.begin(), b.end(), n) == b.end()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

void require_same_names(const std::vector<std::string>& s, const std::vector<std::string>& t,
                        const std::string& what, const std::string& s_file,
                        const std::string& t_file) {
  const std::string only_s = missing(s, t), only_t = missing(t, s);
  if (only_s.empty() && only_t.empty()) return;
  std::string msg = what + " differ between the heads:";
  if (!only_s.empty()) msg += " " + t_file + " lacks " + only_s + " (in " + s_file + ");";
  if (!only_t.empty()) msg += " " + s_file + " lacks " + only_t + " (in " + t_file + ");";
  msg.pop_back();
  throw InputError(msg);
}

std::string landmarks_file(const HeadSpec& h) {
  return h.landmarks.empty() ? h.dir + "/landmarks.yaml" : h.landmarks.front().file;
}

// One commanded value the refinement may move, within [lo, hi].
struct Param {
  enum Kind { kMuscle, kPitch, kYaw, kProtrusion, kLid } kind;
  int index = 0;  // contraction slot or eyelid side
  double lo = 0, hi = 1;
};

double& value(Expression& e, const Param& p) {
  switch (p.kind) {
    case Param::kMuscle:
      return e.contractions[static_cast<std::size_t>(p.index)];
    case Param::kPitch:
      return e.jaw.pitch_rad;
    case Param::kYaw:
      return e.jaw.yaw_rad;
    case Param::kProtrusion:
      return e.jaw.protrusion_m;
    case Param::kLid:
      break;
  }
  return e.eyelid_closure[p.index];
}

// The commands the source pose uses, as target parameters.
std::vector<Param> free_parameters(const Expression& source, const CloneMap& map,
                                   const JawBounds& j, const LidRange (&lids)[2]) {
  std::vector<Param> ps;
  for (std::size_t s = 0; s < source.contractions.size(); ++s)
    if (source.contractions[s] > 0) ps.push_back({Param::kMuscle, map.target_slot[s], 0, 1});
  auto jaw = [&](Param::Kind k, double v, double lo, double hi) {
    if (v != 0 && hi > lo) ps.push_back({k, 0, lo, hi});
  };
  jaw(Param::kPitch, source.jaw.pitch_rad, j.pitch_min, j.pitch_max);
  jaw(Param::kYaw, source.jaw.yaw_rad, j.yaw_min, j.yaw_max);
  jaw(Param::kProtrusion, source.jaw.protrusion_m, j.protrusion_min, j.protrusion_max);
  for (int side = 0; side < 2; ++side)
    if (source.eyelid_closure[side] > 0 && lids[side].max > lids[side].min)
      ps.push_back({Param::kLid, side, lids[side].min, lids[side].max});
  return ps;
}

// Landmarks after o.frames frames from rest holding `e`; true if the last 20 frames moved
// the skin less than 0.01 mm.
bool run(const FaceModel& m, FaceData& d, const Expression& e, const std::vector<int>& lms,
         int frames, std::vector<Vec3>& out) {
  reset_face_data(m, d);
  SteadyStateOptions s;
  s.min_frames = s.max_frames = frames;
  const SteadyStateResult r = run_to_steady_state(m, d, face_input(e), s);
  out.resize(lms.size());
  for (std::size_t i = 0; i < lms.size(); ++i) out[i] = landmark_position(m, d.skin_x, lms[i]);
  return r.converged;
}

CloneError error_of(const Eigen::VectorXd& r_mm, const Eigen::VectorXd& goal_mm) {
  CloneError e;
  const Eigen::Index n = r_mm.size() / 3;
  double sum2 = 0, sum = 0, goal = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = r_mm.segment<3>(3 * i).norm();
    sum2 += a * a;
    sum += a;
    goal += goal_mm.segment<3>(3 * i).norm();
    e.max_mm = std::max(e.max_mm, a);
  }
  e.rms_mm = n > 0 ? std::sqrt(sum2 / static_cast<double>(n)) : 0;
  e.percent = goal > 0 ? 100 * sum / goal : 0;
  return e;
}

// The plain copy: same commands by muscle name, the jaw and lids clamped to the target's
// ranges.
Expression plain_copy(const FaceModel& target, const CloneMap& map, const Expression& pose,
                      const MotionCloneOptions& o) {
  Expression e;
  e.name = pose.name;
  e.contractions.assign(target.spec.commanded.size(), 0.0);
  for (std::size_t s = 0; s < pose.contractions.size(); ++s)
    e.contractions[static_cast<std::size_t>(map.target_slot[s])] = pose.contractions[s];
  e.jaw.pitch_rad = std::clamp(pose.jaw.pitch_rad, o.jaw.pitch_min, o.jaw.pitch_max);
  e.jaw.yaw_rad = std::clamp(pose.jaw.yaw_rad, o.jaw.yaw_min, o.jaw.yaw_max);
  e.jaw.protrusion_m =
      std::clamp(pose.jaw.protrusion_m, o.jaw.protrusion_min, o.jaw.protrusion_max);
  for (int side = 0; side < 2; ++side)
    e.eyelid_closure[side] =
        std::clamp(pose.eyelid_closure[side], o.eyelid[side].min, o.eyelid[side].max);
  return e;
}

// The target's least-squares problem for one pose. Parameters are normalised to [0, 1]
// over their ranges, so one step size and one damping fit contractions, angles and
// lengths alike.
struct PoseFit {
  const FaceModel& target;
  const CloneMap& map;
  const MotionCloneOptions& o;
  CloneWorkspace& w;
  const Eigen::VectorXd& goal;
  const std::vector<Param>& ps;
  Expression& e;         // the commands evaluated
  int& evaluations;      // full-model runs so far
  std::vector<Vec3>& x;  // landmark scratch
  bool settled = true;   // of the last evaluation

  Eigen::Index size() const { return static_cast<Eigen::Index>(ps.size()); }

  void set(const Eigen::VectorXd& u) {
    for (Eigen::Index j = 0; j < size(); ++j) {
      const Param& p = ps[static_cast<std::size_t>(j)];
      value(e, p) = p.lo + u[j] * (p.hi - p.lo);
    }
  }

  Eigen::VectorXd normalised() {
    Eigen::VectorXd u(size());
    for (Eigen::Index j = 0; j < size(); ++j) {
      const Param& p = ps[static_cast<std::size_t>(j)];
      u[j] = (value(e, p) - p.lo) / (p.hi - p.lo);
    }
    return u;
  }

  // The target's residual (mm) under the commands in e.
  Eigen::VectorXd evaluate() {
    settled = run(target, w.target, e, map.target_landmark, o.frames, x);
    ++evaluations;
    Eigen::VectorXd r(goal.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      r.segment<3>(3 * static_cast<Eigen::Index>(i)) =
          (x[i] - w.target_neutral[i]) * kMmPerM -
          goal.segment<3>(3 * static_cast<Eigen::Index>(i));
    return r;
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& u) {
    set(u);
    return evaluate();
  }
};

// Forward differences at u (residual r), stepping back from the top of a range.
Eigen::MatrixXd jacobian(PoseFit& f, const Eigen::VectorXd& u, const Eigen::VectorXd& r) {
  Eigen::MatrixXd J(r.size(), f.size());
  for (Eigen::Index j = 0; j < f.size(); ++j) {
    Eigen::VectorXd v = u;
    const double h = v[j] + f.o.fd_step <= 1 ? f.o.fd_step : -f.o.fd_step;
    v[j] += h;
    J.col(j) = (f.residual(v) - r) / h;
  }
  return J;
}

// Where the search stands: the parameters and residual of the best run, its commands (the
// copy itself until a step improves on it, not u mapped back, which would round the
// copy's values) and whether it settled.
struct FitState {
  Eigen::VectorXd u, r;
  Expression best;
  bool settled = true;
  double lambda = 0;
};

// One Levenberg–Marquardt iteration: up to four projected, damped steps from s.u; true
// (and s updated) at the first that lowers the squared error.
bool improve(PoseFit& f, FitState& s) {
  const Eigen::MatrixXd J = jacobian(f, s.u, s.r);
  const Eigen::MatrixXd A = J.transpose() * J;
  const Eigen::VectorXd g = J.transpose() * s.r;
  for (int attempt = 0; attempt < 4; ++attempt) {
    Eigen::MatrixXd M = A;
    // Marquardt's scaling, with a floor for a command that moves no landmark.
    for (Eigen::Index j = 0; j < f.size(); ++j) M(j, j) += s.lambda * std::max(A(j, j), 1e-6);
    const Eigen::VectorXd next =
        (s.u - M.ldlt().solve(g)).cwiseMax(0.0).cwiseMin(1.0);  // projected onto the box
    if ((next - s.u).norm() < 1e-6) return false;
    const Eigen::VectorXd rn = f.residual(next);
    if (rn.squaredNorm() < s.r.squaredNorm()) {
      s.u = next;
      s.r = rn;
      s.settled = f.settled;
      s.best = f.e;
      s.lambda /= 3;
      return true;
    }
    s.lambda *= 4;
  }
  return false;
}

}  // namespace

JawBounds design_jaw_bounds() {
  return {kJawPitchMinDeg * kDeg,
          kJawPitchMaxDeg * kDeg,
          -kJawYawMaxDeg * kDeg,
          kJawYawMaxDeg * kDeg,
          0,
          kJawProtrusionMaxMm * 1e-3};
}

CloneMap fit_clone_map(const FaceModel& source, const FaceModel& target) {
  const HeadSpec &s = source.spec, &t = target.spec;
  require_same_names(source.landmark_names, target.landmark_names, "landmark names",
                     landmarks_file(s), landmarks_file(t));
  require_same_names(s.commanded, t.commanded, "commanded muscle names", s.dir + "/head.yaml",
                     t.dir + "/head.yaml");
  CloneMap map;
  std::vector<Vec3> p, q;
  for (std::size_t i = 0; i < source.landmark_names.size(); ++i) {
    const int si = static_cast<int>(i), ti = target.landmark_index(source.landmark_names[i]);
    map.source_landmark.push_back(si);
    map.target_landmark.push_back(ti);
    p.push_back(landmark_position(source, source.skin.v, si));
    q.push_back(landmark_position(target, target.skin.v, ti));
  }
  for (const std::string& name : s.commanded)
    map.target_slot.push_back(static_cast<int>(
        std::find(t.commanded.begin(), t.commanded.end(), name) - t.commanded.begin()));
  map.g = fit_rbf(p, q);
  return map;
}

CloneWorkspace make_clone_workspace(const FaceModel& source, const FaceModel& target,
                                    const CloneMap& map, const MotionCloneOptions& o) {
  CloneWorkspace w{make_face_data(source), make_face_data(target), {}, {}};
  Expression rest;
  rest.contractions.assign(source.spec.commanded.size(), 0.0);
  run(source, w.source, rest, map.source_landmark, o.frames, w.source_neutral);
  rest.contractions.assign(target.spec.commanded.size(), 0.0);
  run(target, w.target, rest, map.target_landmark, o.frames, w.target_neutral);
  return w;
}

Eigen::VectorXd clone_goals(const FaceModel& source, const CloneMap& map, const Expression& pose,
                            const MotionCloneOptions& o, CloneWorkspace& w) {
  const std::size_t L = map.source_landmark.size();
  std::vector<Vec3> x;
  run(source, w.source, pose, map.source_landmark, o.frames, x);
  Eigen::VectorXd goal(3 * static_cast<Eigen::Index>(L));
  for (std::size_t i = 0; i < L; ++i) {
    const Vec3 rest = landmark_position(source, source.skin.v, map.source_landmark[i]);
    const Vec3 d = x[i] - w.source_neutral[i];
    goal.segment<3>(3 * static_cast<Eigen::Index>(i)) =
        (map.g.apply(rest + d) - map.g.apply(rest)) * kMmPerM;
  }
  return goal;
}

ClonedPose refine_clone(const FaceModel& target, const CloneMap& map, const Eigen::VectorXd& goal,
                        const Expression& uses, const Expression& start,
                        const MotionCloneOptions& o, CloneWorkspace& w) {
  ClonedPose out;
  out.pose = start;
  const std::vector<Param> ps = free_parameters(uses, map, o.jaw, o.eyelid);
  out.free_parameters = static_cast<int>(ps.size());
  std::vector<Vec3> x;
  PoseFit f{target, map, o, w, goal, ps, out.pose, out.evaluations, x};

  FitState s{f.normalised(), f.evaluate(), out.pose, true, o.lambda};
  s.settled = f.settled;
  out.copy = error_of(s.r, goal);
  while (f.size() > 0 && out.iterations < o.iterations &&
         error_of(s.r, goal).rms_mm > o.skip_rms_mm) {
    ++out.iterations;
    if (!improve(f, s)) break;
  }
  out.pose = s.best;
  out.refined = error_of(s.r, goal);
  out.settled = s.settled;
  return out;
}

ClonedPose clone_pose(const FaceModel& source, const FaceModel& target, const CloneMap& map,
                      const Expression& pose, const MotionCloneOptions& o, CloneWorkspace& w) {
  return refine_clone(target, map, clone_goals(source, map, pose, o, w), pose,
                      plain_copy(target, map, pose, o), o, w);
}

}  // namespace facectl::face
