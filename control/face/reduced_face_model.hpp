// The reduced face for the 1 kHz loop: a fitted response surface from (muscle
// contractions, mandible pitch/yaw/protrusion) to the steady-state displacement of named
// skin control points. Its fit to the full model lives in sim/face (reduced_model_fit.hpp).
// Features: c_i, c_i², c_i³, c_i·pitch, c_i·yaw, c_i·protrusion for every muscle; pitch, yaw,
// protrusion, their squares and pairwise products; and c_i·c_j for muscle pairs that both move some
// control point.
// evaluate() is one small dense matrix-vector product over preallocated storage: no
// allocation, no branches on the data.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace facectl::face {

constexpr std::size_t kFeaturesPerMuscle = 6;  // c, c², c³, c·pitch, c·yaw, c·protrusion
// Jaw terms in scaled units (deg-like and mm-like) so the fit is well conditioned.
constexpr double kPitchScale = 10, kYawScale = 10, kProtrusionScale = 100;

struct ReducedFaceModel {
  std::vector<std::string> muscles;         // head.yaml order
  std::vector<std::string> control_points;  // landmark names
  std::vector<std::array<int, 2>> pairs;    // muscle pairs with an interaction feature
  // (3·control_points) × features, row-major so each output is one contiguous dot product.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> coefficients;
  int feature_count() const { return static_cast<int>(coefficients.cols()); }
};

// One feature column in closed form: coefficient · Π x_var^power. Variables are numbered
// 0..n−1 for the contractions (head.yaml order), n for pitch (rad), n+1 for yaw (rad),
// n+2 for protrusion (m); the coefficient carries the fit's internal jaw scaling.
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
// v = (c_0 … c_{n−1}, pitch, yaw and protrusion in the fit's scaled units, 1): n + 4 values.
void fill_feature_variables(std::span<const double> contractions, double pitch_rad, double yaw_rad,
                            double protrusion_m, std::span<double> v);

struct ReducedFaceWorkspace {
  Eigen::VectorXd features;
};

ReducedFaceWorkspace make_reduced_workspace(const ReducedFaceModel& m);

// Fills w.features for the input (the vector evaluate() multiplies by the
// coefficients), for callers that need only some combinations of the outputs.
void evaluate_features(const ReducedFaceModel& m, ReducedFaceWorkspace& w,
                       std::span<const double> contractions, double pitch_rad, double yaw_rad,
                       double protrusion_m);

// contractions: size = muscles.size(); out_displacements_m: 3·control_points.size(),
// (x, y, z) per point in metres, head frame.
void evaluate(const ReducedFaceModel& m, ReducedFaceWorkspace& w,
              std::span<const double> contractions, double pitch_rad, double yaw_rad,
              double protrusion_m, std::span<double> out_displacements_m);

// Feature count for `muscles` muscles and `pairs` interaction pairs.
int reduced_feature_count(std::size_t muscles, std::size_t pairs);
// The whole feature vector f (reduced_feature_count entries) for one input; the fit builds
// its design matrix with it, evaluate() its input.
void fill_features(std::span<const double> contractions, double pitch_rad, double yaw_rad,
                   double protrusion_m, const std::vector<std::array<int, 2>>& pairs,
                   Eigen::Ref<Eigen::VectorXd> f);

}  // namespace facectl::face
