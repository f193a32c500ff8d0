#include "control/limits/coupled_position_bounds.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>

namespace facectl {

std::uint64_t coupled_position_bounds(const CoupledConstraints& limits,
                                      const ActuatorModel* actuators, const LimiterState* state,
                                      const double* target, double* lo, double* hi) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::uint64_t bounded = 0;
  for (std::size_t c = 0; c < limits.size(); ++c) {
    const CoupledConstraints::Constraint& k = limits.constraint(c);
    for (std::size_t t = 0; t < k.terms; ++t) {
      lo[k.index[t]] = -kInf;
      hi[k.index[t]] = kInf;
      bounded |= std::uint64_t{1} << k.index[t];
    }
  }
  for (std::size_t c = 0; c < limits.size(); ++c) {
    const CoupledConstraints::Constraint& k = limits.constraint(c);
    std::array<double, CoupledConstraints::kMaxTerms> m{}, demand{};
    double committed = 0.0, wanted = 0.0;
    for (std::size_t t = 0; t < k.terms; ++t) {
      const std::size_t i = k.index[t];
      const ActuatorLimits& l = actuators[i].limits;
      m[t] = committed_extreme(l, state[i], k.coeff[t]);
      committed += k.coeff[t] * m[t];
      const double goal = std::clamp(target[i], l.soft_min, l.soft_max);
      demand[t] = std::max(0.0, k.coeff[t] * (goal - m[t]));  // NaN target: no demand
      wanted += demand[t];
    }
    const double slack = std::max(0.0, k.bound - committed);
    const double scale = wanted > slack ? slack / wanted : 1.0;
    const double spare = (slack - std::min(wanted, slack)) / static_cast<double>(k.terms);
    for (std::size_t t = 0; t < k.terms; ++t) {
      const std::size_t i = k.index[t];
      const double bound = m[t] + (demand[t] * scale + spare) / k.coeff[t];
      if (k.coeff[t] > 0.0) {
        hi[i] = std::min(hi[i], bound);
      } else {
        lo[i] = std::max(lo[i], bound);
      }
    }
  }
  for (std::uint64_t bits = bounded; bits != 0; bits &= bits - 1) {
    const auto i = static_cast<std::size_t>(std::countr_zero(bits));
    const ActuatorLimits& l = actuators[i].limits;
    const double coupled_lo = lo[i], coupled_hi = hi[i];
    lo[i] = std::max(lo[i], l.soft_min);
    hi[i] = std::min(hi[i], l.soft_max);
    if (lo[i] > hi[i]) {
      // Outside its soft range with a coupled bound holding it there.
      if (coupled_lo > l.soft_max) hi[i] = lo[i];
      if (coupled_hi < l.soft_min) lo[i] = hi[i];
    }
  }
  return bounded;
}

}  // namespace facectl
