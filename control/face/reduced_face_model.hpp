// The reduced face for the 1 kHz loop: a fitted response surface from (muscle
// contractions, mandible pitch/yaw/protrusion, eyelid closures) to the steady-state
// displacement of named skin control points. Its fit to the full model lives in sim/face
// (reduced_model_fit.hpp). Features: products of up to three of the variables
// v = (c_0 … c_{n−1}, pitch, yaw, protrusion in scaled units, lid_l, lid_r, 1,
// c_0² … c_{n−1}²), listed per model (`features`), so the fit chooses the form: per
// muscle its powers up to c⁴ (c_i²·c_i²) and couplings with the jaw, the jaw's cubic, the
// lids' powers and couplings, and products of muscles that move the same control point.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace facectl::face {

// Jaw terms in scaled units (deg-like and mm-like) so the fit is well conditioned.
constexpr double kPitchScale = 10, kYawScale = 10, kProtrusionScale = 100;

// What the reduced model takes: the full face's inputs, in SI.
struct ReducedInput {
  std::span<const double> contractions;  // head.yaml order, each in [0, 1]
  double pitch_rad = 0, yaw_rad = 0, protrusion_m = 0;
  double eyelid_closure[2] = {0, 0};  // left, right in [0, 1], as face::FaceInput
};

struct ReducedFaceModel {
  std::vector<std::string> muscles;         // head.yaml order
  std::vector<std::string> control_points;  // landmark names
  // Feature k is v[a]·v[b]·v[c] for features[k] = {a, b, c} over fill_feature_variables()'s
  // v; a factor n + 5 is the constant 1, n + 6 + i is c_i². Each triple ascending and
  // listed once.
  std::vector<std::array<int, 3>> features;
  // {file, SHA-256} of the head files the model was fitted to (sim/face checks them at load).
  std::vector<std::array<std::string, 2>> fitted_to;
  // (3·control_points) × features, row-major so each output is one contiguous dot product.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> coefficients;
  int feature_count() const { return static_cast<int>(coefficients.cols()); }
};

// One feature column in closed form: coefficient · Π x_var^power. Variables are numbered
// 0..n−1 for the contractions (head.yaml order), n for pitch (rad), n+1 for yaw (rad),
// n+2 for protrusion (m), n+3 and n+4 for the left and right eyelid closures; the
// coefficient carries the fit's internal jaw scaling.
struct Monomial {
  double coefficient = 1.0;
  std::vector<std::array<int, 2>>
      powers;  // {variable, exponent ≥ 1}, each variable once, ascending
};

// Column k describes feature k of evaluate(): out = coefficients · (feature_monomials
// evaluated at the input). Lives next to the feature code so the two cannot drift; a test
// compares them on random inputs.
std::vector<Monomial> feature_monomials(const ReducedFaceModel& m);
double evaluate_monomial(const Monomial& m, std::span<const double> variables);

// Feature column `column` is the product (v[a]·v[b])·v[c] of its factors {a, b, c} over
// the variables v of fill_feature_variables(), and equals evaluate_features()' column bit
// for bit (a factor of 1 is exact). For callers that need only a few columns (FeatureSubset).
std::array<int, 3> feature_factors(const ReducedFaceModel& m, int column);
// v = (c_0 … c_{n−1}, pitch, yaw and protrusion in the fit's scaled units, lid_l, lid_r,
// 1, c_0² … c_{n−1}²): variable_count(n) = 2n + 6 values.
void fill_feature_variables(const ReducedInput& in, std::span<double> v);

struct ReducedFaceWorkspace {
  Eigen::VectorXd variables;  // variable_count(n), as fill_feature_variables()
  Eigen::VectorXd features;
};

ReducedFaceWorkspace make_reduced_workspace(const ReducedFaceModel& m);

// Fills w.features for the input (the vector evaluate() multiplies by the
// coefficients), for callers that need only some combinations of the outputs.
void evaluate_features(const ReducedFaceModel& m, ReducedFaceWorkspace& w, const ReducedInput& in);

// in.contractions: size = muscles.size(); out_displacements_m: 3·control_points.size(),
// (x, y, z) per point in metres, head frame.
void evaluate(const ReducedFaceModel& m, ReducedFaceWorkspace& w, const ReducedInput& in,
              std::span<double> out_displacements_m);

// The variable of the eyelid closure of `side` (0 left, 1 right) for `muscles` muscles.
inline int lid_variable(std::size_t muscles, int side) {
  return static_cast<int>(muscles) + 3 + side;
}
// The index of the constant variable 1 for `muscles` muscles.
inline int constant_variable(std::size_t muscles) {
  return static_cast<int>(muscles) + 5;
}
// The variable that holds c_i² (derived from c_i, so a triple of factors reaches c⁴: an
// S-shaped response such as a nostril under its levator needs it).
inline int square_variable(std::size_t muscles, int i) {
  return constant_variable(muscles) + 1 + i;
}
// How many variables fill_feature_variables() writes for `muscles` muscles.
inline int variable_count(std::size_t muscles) {
  return square_variable(muscles, static_cast<int>(muscles));
}
// The feature vector f (one entry per triple) from the variables v.
void fill_features(std::span<const double> v, const std::vector<std::array<int, 3>>& features,
                   Eigen::Ref<Eigen::VectorXd> f);

}  // namespace facectl::face
