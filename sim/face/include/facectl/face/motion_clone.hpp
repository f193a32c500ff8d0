// Facial motion cloning (thesis ch. 6) for muscle-driven heads: a pose (an expression or a
// viseme) of one head becomes contractions, jaw and eyelids of another head whose
// steady-state landmark displacements match the source's, carried over by the RBF G that
// maps the source's rest landmarks onto the target's. The thesis copies vertex motion; a
// muscle head can only take commands, so the copy is an inverse problem on the target's
// full model (docs/FACE_MODEL.md, "Motion cloning").
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/face_model.hpp"
#include "facectl/face/rbf_morph.hpp"

namespace facectl::face {

// Per-axis range of the target's mandible (SI), from its head.yaml envelope.
struct JawBounds {
  double pitch_min = 0, pitch_max = 0, yaw_min = 0, yaw_max = 0, protrusion_min = 0,
         protrusion_max = 0;
};
// The design limits (control/envelope/mandible_envelope.hpp), which every head narrows.
JawBounds design_jaw_bounds();

// The range of one eyelid's closure command (head.yaml `rigid: eyelid_closure`).
struct LidRange {
  double min = 0, max = 1;
};

struct MotionCloneOptions {
  // Full-model frames from rest for one evaluation. A fixed count, not a tolerance, so that
  // a finite difference compares two runs of the same length (a tolerance stop would
  // add a step of its own to the difference).
  int frames = 200;
  int iterations = 3;         // Levenberg–Marquardt Jacobians at most
  double fd_step = 0.03;      // finite-difference step, in units of each parameter's range
  double lambda = 1e-2;       // initial damping, relative to diag(JᵀJ)
  double skip_rms_mm = 1e-6;  // a plain copy this close is kept as it is (the self-clone)
  JawBounds jaw = design_jaw_bounds();
  LidRange eyelid[2];  // left, right
};

// How the two heads correspond: landmarks and commanded muscles matched by name, and G.
struct CloneMap {
  std::vector<int> source_landmark, target_landmark;  // model landmark indices, paired
  std::vector<int> target_slot;                       // target contraction slot of each source slot
  RbfMorph g;  // source rest landmarks → target rest landmarks (m)
};

// Throws InputError naming the landmarks or commanded muscles that one head has and the
// other lacks, and std::invalid_argument when G cannot be fitted (coplanar landmarks).
CloneMap fit_clone_map(const FaceModel& source, const FaceModel& target);

struct CloneError {
  double rms_mm = 0, max_mm = 0;  // over landmarks, |target displacement − goal|
  double percent = 0;             // thesis Eq. 6.1: Σ|error| / Σ|goal| · 100 (0 for no goal)
};

struct ClonedPose {
  Expression pose;           // in the target's commanded order
  CloneError copy, refined;  // the plain copy of the commands, and after refinement
  int free_parameters = 0, iterations = 0, evaluations = 0;
  bool settled = true;  // every run of the final pose moved < 0.01 mm over its last 20 frames
};

// Buffers for one pair of heads, reused across poses.
struct CloneWorkspace {
  FaceData source, target;
  std::vector<Vec3> source_neutral, target_neutral;  // landmarks after `frames` at rest
};
CloneWorkspace make_clone_workspace(const FaceModel& source, const FaceModel& target,
                                    const CloneMap& map, const MotionCloneOptions& o);

// Clones one pose: the source's landmark displacements from its neutral run, d_i, become
// goals t_i = G(P_i + d_i) − G(P_i) on the target; the target starts from the same
// commands (jaw and eyelids clamped to o.jaw and o.eyelid) and Levenberg–Marquardt with forward
// differences moves the commands the pose uses (non-zero contractions, jaw axes and eyelids) within
// their ranges to fit t_i.
ClonedPose clone_pose(const FaceModel& source, const FaceModel& target, const CloneMap& map,
                      const Expression& pose, const MotionCloneOptions& o, CloneWorkspace& w);

// clone_pose's two halves. The goals t_i (mm, x y z per landmark pair) of `pose`:
Eigen::VectorXd clone_goals(const FaceModel& source, const CloneMap& map, const Expression& pose,
                            const MotionCloneOptions& o, CloneWorkspace& w);
// The refinement from `start` (target order; clone_pose starts from the plain copy),
// moving the commands the source pose `uses` sets; ClonedPose::copy is the error at start.
ClonedPose refine_clone(const FaceModel& target, const CloneMap& map, const Eigen::VectorXd& goal,
                        const Expression& uses, const Expression& start,
                        const MotionCloneOptions& o, CloneWorkspace& w);

}  // namespace facectl::face
