// Automatic actuator placement (issue #20, item 6): which N skin points, each moved along
// one direction by a 1-DOF actuator, best reproduce the library's expressions on the full
// model. Targets are steady states of the full model; the choice is a greedy least-squares
// selection over linearised responses to single pinned points; the result is validated by
// pinning the chosen points in the full model (docs/FACE_MODEL.md, "Placing actuators").
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "facectl/face/expression_library.hpp"
#include "facectl/face/face_model.hpp"
#include "facectl/face/steady_state.hpp"

namespace facectl::face {

struct PlacementOptions {
  std::vector<std::string> expressions;  // library names to reproduce; empty = all
  double moving_threshold_mm = 0.5;      // a vertex moves when some |D_e| exceeds this
  int max_candidate_vertices = 200;      // farthest-point subsample of the moving vertices
  int directions = 2;                    // principal directions tried per candidate vertex
  double step_mm = 2;                    // pin displacement of a response run
  SteadyStateOptions steady;
};

// The costly part, shared by every budget: targets and responses, all in metres.
struct PlacementProblem {
  double step_m = 0.002;
  SteadyStateOptions steady;
  FaceData settled;  // neutral at steady state: every run starts here
  Points rest;       // its skin
  std::vector<Expression> expressions;
  std::vector<Points> full, jaw_only;  // per expression: all inputs; jaw and lids alone
  std::vector<int> moving;             // vertices the errors are measured on
  std::vector<int> candidate_vertex;   // per candidate (vertex, direction)
  std::vector<Vec3> candidate_axis;
  // Rows 3·i + c: coordinate c of moving[i]. target.col(e) = full − jaw_only (the soft
  // tissue the actuators must produce); response.col(k) = skin displacement per step.
  Eigen::MatrixXd target, response;
  int runs = 0, unsettled = 0;
};

struct PlacedActuator {
  int vertex = -1;
  std::string landmark;  // a landmark that is exactly this vertex, else empty
  std::string nearest_control_point;
  double control_point_distance_mm = 0;
  Vec3 position_mm = Vec3::Zero();  // settled neutral, model (head) frame
  Vec3 axis = Vec3::UnitX();
  double travel_min_mm = 0, travel_max_mm = 0;  // across the expressions
};

struct ExpressionFit {
  std::string name;
  double rms_mm = 0, max_mm = 0;    // pinned full model vs the expression, moving vertices
  double rms0_mm = 0, max0_mm = 0;  // with no actuators (jaw and lids alone)
  int worst_vertex = -1;            // where max_mm is
  std::vector<double> travel_mm;    // per actuator
  bool settled = true;
};

struct Placement {
  std::vector<PlacedActuator> actuators;
  std::vector<ExpressionFit> fits;
  int unsettled = 0;  // validation runs that hit the frame cap
};

using PlacementProgress = std::function<void(const std::string&)>;

// Throws InputError for an expression name not in the library.
PlacementProblem build_placement_problem(const FaceModel& m, const ExpressionLibrary& lib,
                                         const PlacementOptions& o,
                                         const PlacementProgress& progress = {});
// Chooses up to `budget` actuators (one per vertex; fewer if the candidates run out) and
// validates them on the full model.
Placement place_actuators(const FaceModel& m, const PlacementProblem& p, int budget,
                          const PlacementProgress& progress = {});

// The jaw and eyelid part of an expression: its mandible pose and its eyelid closures
// (with the orbicularis oculi's lid coupling folded in), muscles relaxed.
FaceInput jaw_and_lids_input(const FaceModel& m, const Expression& e);

}  // namespace facectl::face
