#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace facectl::verify {

// The admissible face set as a polytope: a box per variable and linear
// inequalities rows·x <= rhs (dense rows).
struct Polytope {
  std::vector<double> lo, hi;
  std::vector<std::vector<double>> rows;
  std::vector<double> rhs;
  std::size_t size() const { return lo.size(); }
};

struct Extremum {
  double value = 0.0;
  std::vector<double> at;  // a point of the polytope where it is attained
};

// The exact maximum of c·x over the polytope (GLPK's simplex, then its exact
// rational simplex to certify the optimum). nullopt if the polytope is empty.
std::optional<Extremum> maximize(const Polytope& p, const std::vector<double>& c);
std::optional<Extremum> minimize(const Polytope& p, const std::vector<double>& c);

// Frees GLPK's environment of the calling thread (GLPK keeps one per thread and builds it
// again on the next call). A thread that solved and then ends calls it, or the environment
// leaks with the thread.
void release_lp_thread_state();

}  // namespace facectl::verify
