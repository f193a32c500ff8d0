// An actuator channel driven by the reduced face model, collapsed into one sparse
// polynomial over the face variables, so that `facectl verify` can bound it.
//
//   q = offset + Σ_k gain_k · (disp(point_k) · axis_k) + Σ_j gain_j · x_{variable_j}
//
// Variables (SI): 0..n−1 the muscle contractions in head.yaml order, n mandible pitch (rad),
// n+1 yaw (rad), n+2 protrusion (m), n+3 and n+4 the eyelid closures: the reduced model's
// variables without its constant and derived squares (face::feature_monomials writes a
// square as its contraction to the power 2). disp() is the reduced model's control-point
// displacement in metres, so a gain of 1000 gives millimetres.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "control/face/reduced_face_model.hpp"

namespace facectl::verify {

struct ControlPointTerm {
  int control_point = 0;         // index into ReducedFaceModel::control_points
  std::array<double, 3> axis{};  // unit vector, head frame
  double gain = 1.0;
};

struct LinearTerm {
  int variable = 0;  // numbering above
  double gain = 0.0;
};

struct ChannelTerms {
  double offset = 0.0;
  std::vector<ControlPointTerm> points;
  std::vector<LinearTerm> linear;
};

struct PolynomialTerm {
  face::Monomial monomial;  // coefficient · Π x^power
  // Σ |contribution| of everything merged into this term, as the tick evaluates it
  // unmerged: scales the floating-point slack of a bound (docs/VERIFY.md).
  double magnitude = 0.0;
};

struct ChannelPolynomial {
  int variable_count = 0;  // muscles + 5
  double constant = 0.0;
  // Distinct monomials, sorted by powers. A term whose contributions cancelled exactly keeps
  // coefficient 0 for its magnitude (the tick still evaluates and rounds them).
  std::vector<PolynomialTerm> terms;

  double evaluate(std::span<const double> variables) const;
  // Ascending indices of the variables some term with a non-zero coefficient uses.
  std::vector<int> used_variables() const;
};

// Throws std::invalid_argument for a control point or variable out of range, an axis that
// is not a unit vector (|‖axis‖ − 1| > 1e-9), or a non-finite gain or offset.
ChannelPolynomial make_channel_polynomial(const face::ReducedFaceModel& model,
                                          const ChannelTerms& terms);

}  // namespace facectl::verify
