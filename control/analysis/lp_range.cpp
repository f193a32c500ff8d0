#include "control/analysis/lp_range.hpp"

#include <glpk.h>

#include <memory>
#include <stdexcept>

namespace facectl::verify {
namespace {

struct ProblemDeleter {
  void operator()(glp_prob* p) const { glp_delete_prob(p); }
};

// Without inequalities the box alone decides: each variable at the bound its
// coefficient favours (GLPK's exact simplex needs at least one row).
Extremum box_optimum(const Polytope& p, const std::vector<double>& c, int direction) {
  Extremum e;
  e.at.resize(p.size());
  for (std::size_t j = 0; j < p.size(); ++j) {
    const bool up = (c[j] > 0.0) == (direction == GLP_MAX);
    e.at[j] = c[j] == 0.0 ? p.lo[j] : (up ? p.hi[j] : p.lo[j]);
    e.value += c[j] * e.at[j];
  }
  return e;
}

std::optional<Extremum> optimize(const Polytope& p, const std::vector<double>& c, int direction) {
  for (std::size_t j = 0; j < p.size(); ++j) {
    if (p.lo[j] > p.hi[j]) return std::nullopt;
  }
  if (p.rows.empty()) return box_optimum(p, c, direction);
  const int n = static_cast<int>(p.size());
  const int m = static_cast<int>(p.rows.size());
  std::unique_ptr<glp_prob, ProblemDeleter> lp(glp_create_prob());
  glp_set_obj_dir(lp.get(), direction);
  glp_add_cols(lp.get(), n);
  for (int j = 1; j <= n; ++j) {
    const double lo = p.lo[static_cast<std::size_t>(j - 1)];
    const double hi = p.hi[static_cast<std::size_t>(j - 1)];
    glp_set_col_bnds(lp.get(), j, lo == hi ? GLP_FX : GLP_DB, lo, hi);
    glp_set_obj_coef(lp.get(), j, c[static_cast<std::size_t>(j - 1)]);
  }
  if (m > 0) glp_add_rows(lp.get(), m);
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  for (int i = 1; i <= m; ++i) {
    glp_set_row_bnds(lp.get(), i, GLP_UP, 0.0, p.rhs[static_cast<std::size_t>(i - 1)]);
    const auto& row = p.rows[static_cast<std::size_t>(i - 1)];
    for (int j = 1; j <= n; ++j) {
      if (row[static_cast<std::size_t>(j - 1)] == 0.0) continue;
      ia.push_back(i);
      ja.push_back(j);
      ar.push_back(row[static_cast<std::size_t>(j - 1)]);
    }
  }
  glp_load_matrix(lp.get(), static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());
  glp_smcp params;
  glp_init_smcp(&params);
  params.msg_lev = GLP_MSG_OFF;
  params.presolve = GLP_OFF;
  glp_term_out(GLP_OFF);
  if (glp_simplex(lp.get(), &params) != 0) throw std::runtime_error("GLPK simplex failed");
  // Certify the floating-point optimum in exact rational arithmetic.
  if (glp_exact(lp.get(), &params) != 0) throw std::runtime_error("GLPK exact simplex failed");
  const int status = glp_get_status(lp.get());
  if (status == GLP_NOFEAS) return std::nullopt;
  if (status != GLP_OPT) throw std::runtime_error("GLPK: no optimum (unbounded?)");
  Extremum e;
  e.value = glp_get_obj_val(lp.get());
  e.at.resize(p.size());
  for (int j = 1; j <= n; ++j)
    e.at[static_cast<std::size_t>(j - 1)] = glp_get_col_prim(lp.get(), j);
  return e;
}

}  // namespace

std::optional<Extremum> maximize(const Polytope& p, const std::vector<double>& c) {
  return optimize(p, c, GLP_MAX);
}

std::optional<Extremum> minimize(const Polytope& p, const std::vector<double>& c) {
  return optimize(p, c, GLP_MIN);
}

void release_lp_thread_state() {
  glp_free_env();
}

}  // namespace facectl::verify
