#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace facectl {

// Linear inequalities Σ a_k·x_{i_k} <= b over a vector (face signals or
// actuator positions), with a box lo <= x <= hi, enforced in the tick by a
// deterministic, bounded-time projection:
//   1. a fixed number of cyclic projections onto the violated half-spaces and
//      the box (Gauss–Seidel, in constraint order), which approaches the
//      nearest admissible point;
//   2. a repair that is exact: per group of coupled variables still in
//      violation, the point moves along the segment toward `reference` (a pose
//      the configuration proved admissible) to the first admissible point.
// The result always satisfies every constraint and the box.
class CoupledConstraints {
 public:
  static constexpr std::size_t kMaxConstraints = 32;
  static constexpr std::size_t kMaxTerms = 4;
  static constexpr std::size_t kMaxVariables = 96;
  static constexpr int kIterations = 16;

  struct Constraint {
    std::string name;  // for reports; not touched in the tick
    std::array<std::size_t, kMaxTerms> index{};
    std::array<double, kMaxTerms> coeff{};
    std::size_t terms = 0;
    double bound = 0.0;
    double value(const double* x) const;
  };

  // Throws std::invalid_argument on a bad constraint (too many terms, a zero row).
  void add(const Constraint& c);
  // Call once after the last add(): sets the box and the admissible reference
  // point, groups coupled variables, and checks that the reference satisfies
  // everything (throws std::invalid_argument naming the constraint if not).
  void finalize(std::size_t variables, const double* lo, const double* hi, const double* reference);

  std::size_t size() const { return count_; }
  const Constraint& constraint(std::size_t i) const { return constraints_[i]; }

  // Projects x in place. Returns a bit per constraint that was violated on
  // entry (bit i = constraint i), and writes the largest violation to *worst.
  std::uint32_t project(double* x, double* worst = nullptr) const;

 private:
  std::array<Constraint, kMaxConstraints> constraints_{};
  std::size_t count_ = 0;
  std::size_t variables_ = 0;
  std::array<double, kMaxVariables> lo_{};
  std::array<double, kMaxVariables> hi_{};
  std::array<double, kMaxVariables> reference_{};
  std::array<int, kMaxConstraints> group_{};  // connected component of each constraint
  std::array<int, kMaxVariables> var_group_{};
  int groups_ = 0;
};

}  // namespace facectl
