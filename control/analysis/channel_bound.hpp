// A proven range for one polynomial channel over the admissible face set: a box of
// variable intervals (muscles [0,1], the mandible envelope) intersected with linear
// inequalities (coupled limits), by branch and bound on interval enclosures.
// Method, soundness argument and floating-point slack: docs/VERIFY.md.
#pragma once

#include <span>
#include <vector>

#include "control/analysis/channel_polynomial.hpp"
#include "control/analysis/interval.hpp"

namespace facectl::verify {

// Σ_v a[v]·x_v ≤ b, with a over all ChannelPolynomial::variable_count variables.
struct LinearInequality {
  std::vector<double> a;
  double b = 0.0;
};

struct BoundOptions {
  // Stop a side once proven bound − attained value ≤ tolerance (channel units).
  double tolerance = 1e-6;
  // Boxes each side (upper, lower) may process before it reports the bound it has.
  long max_boxes = 600000;
};

// The rounding slack added outside every proven bound: kRelativeSlack · M + kAbsoluteSlack,
// where M = Σ_terms magnitude · Π max|x_v|^power over the box (docs/VERIFY.md).
inline constexpr double kRelativeSlack = 1e-10;
inline constexpr double kAbsoluteSlack = 1e-12;

struct ChannelBound {
  // Proven: every admissible x gives lower ≤ q(x) ≤ upper (slack included). When the
  // admissible set is proven empty, lower = +inf, upper = −inf.
  double lower = 0.0, upper = 0.0;
  // q at admissible witnesses (NaN, witnesses empty, when none was found).
  double attained_min = 0.0, attained_max = 0.0;
  std::vector<double> witness_min, witness_max;  // variable_count values each
  long boxes_used = 0;                           // both sides
  bool converged = false;                        // both sides: bound − attained ≤ tolerance
  bool empty = false;                            // the admissible set is proven empty
};

// box: variable_count intervals. Throws std::invalid_argument on a size mismatch, an empty
// or non-finite interval, or a non-finite constraint. Deterministic.
ChannelBound bound_channel(const ChannelPolynomial& p, std::span<const Interval> box,
                           std::span<const LinearInequality> constraints,
                           const BoundOptions& options = {});

}  // namespace facectl::verify
