#include "control/limits/coupled_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace facectl {
namespace {

// Slack below which a constraint counts as satisfied (rounding).
constexpr double kTolerance = 1e-12;

}  // namespace

double CoupledConstraints::Constraint::value(const double* x) const {
  double v = 0.0;
  for (std::size_t k = 0; k < terms; ++k) v += coeff[k] * x[index[k]];
  return v;
}

void CoupledConstraints::add(const Constraint& c) {
  if (count_ == kMaxConstraints) throw std::invalid_argument("too many coupled constraints");
  if (c.terms == 0 || c.terms > kMaxTerms) {
    throw std::invalid_argument("constraint '" + c.name + "': needs 1.." +
                                std::to_string(kMaxTerms) + " terms");
  }
  double norm = 0.0;
  for (std::size_t k = 0; k < c.terms; ++k) {
    if (c.index[k] >= kMaxVariables) throw std::invalid_argument("constraint index out of range");
    norm += c.coeff[k] * c.coeff[k];
  }
  if (norm == 0.0) throw std::invalid_argument("constraint '" + c.name + "': all coefficients 0");
  constraints_[count_++] = c;
}

void CoupledConstraints::finalize(std::size_t variables, const double* lo, const double* hi,
                                  const double* reference) {
  if (variables > kMaxVariables) throw std::invalid_argument("too many variables");
  variables_ = variables;
  std::copy_n(lo, variables, lo_.begin());
  std::copy_n(hi, variables, hi_.begin());
  std::copy_n(reference, variables, reference_.begin());
  for (std::size_t i = 0; i < variables; ++i) {
    if (reference[i] < lo[i] || reference[i] > hi[i]) {
      throw std::invalid_argument("the reference pose is outside the box at variable " +
                                  std::to_string(i));
    }
  }
  for (std::size_t c = 0; c < count_; ++c) {
    if (constraints_[c].value(reference) > constraints_[c].bound + kTolerance) {
      throw std::invalid_argument("constraint '" + constraints_[c].name +
                                  "' does not hold at the reference pose");
    }
  }
  // Connected components of the variable-constraint graph (union of variables
  // that share a constraint), so that a repair moves only what is coupled.
  var_group_.fill(-1);
  groups_ = 0;
  for (std::size_t c = 0; c < count_; ++c) {
    int g = -1;
    for (std::size_t k = 0; k < constraints_[c].terms; ++k) {
      g = std::max(g, var_group_[constraints_[c].index[k]]);
    }
    if (g < 0) g = groups_++;
    for (std::size_t k = 0; k < constraints_[c].terms; ++k) {
      const int old = var_group_[constraints_[c].index[k]];
      if (old >= 0 && old != g) {
        for (auto& vg : var_group_) {
          if (vg == old) vg = g;
        }
      }
      var_group_[constraints_[c].index[k]] = g;
    }
  }
  for (std::size_t c = 0; c < count_; ++c) group_[c] = var_group_[constraints_[c].index[0]];
}

std::uint32_t CoupledConstraints::project(double* x, double* worst) const {
  std::uint32_t fired = 0;
  double worst_violation = 0.0;
  for (std::size_t c = 0; c < count_; ++c) {
    const double violation = constraints_[c].value(x) - constraints_[c].bound;
    if (violation > kTolerance) {
      fired |= 1u << c;
      worst_violation = std::max(worst_violation, violation);
    }
  }
  if (worst != nullptr) *worst = worst_violation;
  if (fired == 0) return 0;
  for (std::size_t i = 0; i < variables_; ++i) x[i] = std::clamp(x[i], lo_[i], hi_[i]);

  // 1. Cyclic projection onto violated half-spaces, then the box.
  for (int it = 0; it < kIterations; ++it) {
    bool any = false;
    for (std::size_t c = 0; c < count_; ++c) {
      const Constraint& k = constraints_[c];
      const double violation = k.value(x) - k.bound;
      if (violation <= kTolerance) continue;
      any = true;
      double norm = 0.0;
      for (std::size_t t = 0; t < k.terms; ++t) norm += k.coeff[t] * k.coeff[t];
      for (std::size_t t = 0; t < k.terms; ++t) {
        const std::size_t i = k.index[t];
        x[i] = std::clamp(x[i] - violation * k.coeff[t] / norm, lo_[i], hi_[i]);
      }
    }
    if (!any) return fired;
  }

  // 2. Exact repair along the segment to the reference, per coupled group.
  for (int g = 0; g < groups_; ++g) {
    double t = 1.0;  // fraction of the way from the reference to x that is kept
    for (std::size_t c = 0; c < count_; ++c) {
      if (group_[c] != g) continue;
      const Constraint& k = constraints_[c];
      const double at_x = k.value(x);
      if (at_x <= k.bound + kTolerance) continue;
      const double at_ref = k.value(reference_.data());
      // at_ref + t·(at_x − at_ref) <= bound, with at_ref <= bound < at_x.
      t = std::min(t, (k.bound - at_ref) / (at_x - at_ref));
    }
    if (t >= 1.0) continue;
    t = std::max(0.0, t);
    for (std::size_t i = 0; i < variables_; ++i) {
      if (var_group_[i] == g) x[i] = reference_[i] + t * (x[i] - reference_[i]);
    }
  }
  return fired;
}

}  // namespace facectl
