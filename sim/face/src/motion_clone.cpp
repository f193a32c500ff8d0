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
                                   const JawBounds& j) {
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
    if (source.eyelid_closure[side] > 0) ps.push_back({Param::kLid, side, 0, 1});
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

ClonedPose clone_pose(const FaceModel& source, const FaceModel& target, const CloneMap& map,
                      const Expression& pose, const MotionCloneOptions& o, CloneWorkspace& w) {
  const std::size_t L = map.source_landmark.size();
  // Goals: the source's displacements through G's local behaviour at each landmark.
  std::vector<Vec3> x;
  run(source, w.source, pose, map.source_landmark, o.frames, x);
  Eigen::VectorXd goal(3 * static_cast<Eigen::Index>(L));
  for (std::size_t i = 0; i < L; ++i) {
    const Vec3 rest = landmark_position(source, source.skin.v, map.source_landmark[i]);
    const Vec3 d = x[i] - w.source_neutral[i];
    goal.segment<3>(3 * static_cast<Eigen::Index>(i)) =
        (map.g.apply(rest + d) - map.g.apply(rest)) * kMmPerM;
  }

  // The plain copy: same commands by muscle name, the jaw clamped to the target's range.
  ClonedPose out;
  Expression& e = out.pose;
  e.name = pose.name;
  e.contractions.assign(target.spec.commanded.size(), 0.0);
  for (std::size_t s = 0; s < pose.contractions.size(); ++s)
    e.contractions[static_cast<std::size_t>(map.target_slot[s])] = pose.contractions[s];
  e.jaw.pitch_rad = std::clamp(pose.jaw.pitch_rad, o.jaw.pitch_min, o.jaw.pitch_max);
  e.jaw.yaw_rad = std::clamp(pose.jaw.yaw_rad, o.jaw.yaw_min, o.jaw.yaw_max);
  e.jaw.protrusion_m =
      std::clamp(pose.jaw.protrusion_m, o.jaw.protrusion_min, o.jaw.protrusion_max);
  e.eyelid_closure[0] = pose.eyelid_closure[0];
  e.eyelid_closure[1] = pose.eyelid_closure[1];

  const std::vector<Param> ps = free_parameters(pose, map, o.jaw);
  const auto k = static_cast<Eigen::Index>(ps.size());
  out.free_parameters = static_cast<int>(k);

  // Parameters normalised to [0, 1] over their ranges, so one step size and one damping
  // fit contractions, angles and lengths alike.
  auto set = [&](const Eigen::VectorXd& u) {
    for (Eigen::Index j = 0; j < k; ++j) {
      const Param& p = ps[static_cast<std::size_t>(j)];
      value(e, p) = p.lo + u[j] * (p.hi - p.lo);
    }
  };
  bool settled = true;
  auto evaluate = [&] {  // the target's residual (mm) under the commands in e
    settled = run(target, w.target, e, map.target_landmark, o.frames, x);
    ++out.evaluations;
    Eigen::VectorXd r(goal.size());
    for (std::size_t i = 0; i < L; ++i)
      r.segment<3>(3 * static_cast<Eigen::Index>(i)) =
          (x[i] - w.target_neutral[i]) * kMmPerM -
          goal.segment<3>(3 * static_cast<Eigen::Index>(i));
    return r;
  };
  auto residual = [&](const Eigen::VectorXd& u) {
    set(u);
    return evaluate();
  };

  Eigen::VectorXd u(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const Param& p = ps[static_cast<std::size_t>(j)];
    u[j] = (value(e, p) - p.lo) / (p.hi - p.lo);
  }
  // The commands of the best run so far: the copy itself until a step improves on it (not
  // u mapped back, which would round the copy's values).
  Expression best = e;
  Eigen::VectorXd r = evaluate();
  bool r_settled = settled;
  out.copy = error_of(r, goal);
  double lambda = o.lambda;
  while (k > 0 && out.iterations < o.iterations && error_of(r, goal).rms_mm > o.skip_rms_mm) {
    ++out.iterations;
    Eigen::MatrixXd J(r.size(), k);
    for (Eigen::Index j = 0; j < k; ++j) {
      Eigen::VectorXd v = u;
      const double h = v[j] + o.fd_step <= 1 ? o.fd_step : -o.fd_step;
      v[j] += h;
      J.col(j) = (residual(v) - r) / h;
    }
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 4 && !improved; ++attempt) {
      Eigen::MatrixXd M = A;
      // Marquardt's scaling, with a floor for a command that moves no landmark.
      for (Eigen::Index j = 0; j < k; ++j) M(j, j) += lambda * std::max(A(j, j), 1e-6);
      const Eigen::VectorXd next =
          (u - M.ldlt().solve(g)).cwiseMax(0.0).cwiseMin(1.0);  // projected onto the box
      if ((next - u).norm() < 1e-6) break;
      const Eigen::VectorXd rn = residual(next);
      if (rn.squaredNorm() < r.squaredNorm()) {
        u = next;
        r = rn;
        r_settled = settled;
        best = e;
        lambda /= 3;
        improved = true;
      } else {
        lambda *= 4;
      }
    }
    if (!improved) break;
  }
  e = best;
  out.refined = error_of(r, goal);
  out.settled = r_settled;
  return out;
}

}  // namespace facectl::face
