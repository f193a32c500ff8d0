#include "control/analysis/channel_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>

namespace facectl::verify {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Relative rounding margin of a constraint test or tightening step (docs/VERIFY.md).
constexpr double kRowMargin = 1e-12;

using Powers = std::vector<std::array<int, 2>>;
struct LocalTerm {
  double coefficient;
  Powers powers;  // over search dimensions
};

// Exact range (up to rounding) of c1·x + c2·x² + c3·x³ over x: the endpoints and the
// roots of the derivative inside the interval.
Interval cubic_range(double c1, double c2, double c3, Interval x) {
  auto g = [&](double t) { return t * (c1 + t * (c2 + t * c3)); };
  double a = g(x.lo), b = g(x.hi);
  Interval r{std::min(a, b), std::max(a, b)};
  if (x.lo == x.hi) return r;
  auto consider = [&](double t) {
    if (t > x.lo && t < x.hi) {
      const double v = g(t);
      r.lo = std::min(r.lo, v);
      r.hi = std::max(r.hi, v);
    }
  };
  if (c3 != 0.0) {
    // 3c3·t² + 2c2·t + c1 = 0, in the cancellation-free form.
    const double disc = c2 * c2 - 3.0 * c3 * c1;
    if (disc >= 0.0) {
      const double q = -(c2 + std::copysign(std::sqrt(disc), c2));
      if (q != 0.0) {
        consider(q / (3.0 * c3));
        consider(c1 / q);
      } else {
        consider(0.0);
      }
    }
  } else if (c2 != 0.0) {
    consider(-c1 / (2.0 * c2));
  }
  return r;
}

// The largest value of g·t + a·t²/2 over |t| ≤ r: at an end, or at the vertex when the
// parabola opens downwards and its vertex lies inside.
double quadratic_max(double g, double a, double r) {
  double m = std::fabs(g) * r + 0.5 * a * r * r;
  if (a < 0 && std::fabs(g) < -a * r) m = std::max(m, g * g / (-2.0 * a));
  return m;
}

// A sparse polynomial over the search dimensions, split into a constant, one cubic per
// dimension (evaluated exactly on an interval) and cross terms (interval products).
class Compiled {
 public:
  Compiled() = default;
  Compiled(int dims, const std::vector<LocalTerm>& terms) {
    std::vector<std::array<double, 3>> uni(static_cast<std::size_t>(dims), {0, 0, 0});
    std::vector<char> has(static_cast<std::size_t>(dims), 0);
    for (const LocalTerm& t : terms) {
      if (t.coefficient == 0.0) continue;
      if (t.powers.empty()) {
        constant_ += t.coefficient;
      } else if (t.powers.size() == 1 && t.powers[0][1] <= 3) {
        const auto d = static_cast<std::size_t>(t.powers[0][0]);
        uni[d][static_cast<std::size_t>(t.powers[0][1] - 1)] += t.coefficient;
        has[d] = 1;
      } else {
        cross_.push_back(
            {t.coefficient, static_cast<int>(factors_.size()), static_cast<int>(t.powers.size())});
        factors_.insert(factors_.end(), t.powers.begin(), t.powers.end());
      }
    }
    has_uni_ = has;
    for (int d = 0; d < dims; ++d)
      if (has[static_cast<std::size_t>(d)]) {
        uni_dim_.push_back(d);
        uni_.push_back(uni[static_cast<std::size_t>(d)]);
      }
  }

  // The enclosure of f(x) + Σ_d shift[d]·x_d over the box (shift may be null). A shift on a
  // dimension with a univariate part joins that cubic before its exact range is taken.
  Interval enclose(const Interval* box, const double* shift = nullptr) const {
    Interval r{constant_, constant_};
    for (std::size_t k = 0; k < uni_dim_.size(); ++k) {
      const int d = uni_dim_[k];
      r = r + cubic_range(uni_[k][0] + (shift ? shift[d] : 0.0), uni_[k][1], uni_[k][2], box[d]);
    }
    if (shift)
      for (std::size_t d = 0; d < has_uni_.size(); ++d)
        if (!has_uni_[d] && shift[d] != 0.0) r = r + shift[d] * box[d];
    for (const Cross& c : cross_) {
      Interval p{c.coefficient, c.coefficient};
      for (int f = c.first; f < c.first + c.count; ++f)
        p = p * pow(box[factors_[static_cast<std::size_t>(f)][0]],
                    factors_[static_cast<std::size_t>(f)][1]);
      r = r + p;
    }
    return r;
  }

  double value(const double* x) const {
    double r = constant_;
    for (std::size_t k = 0; k < uni_dim_.size(); ++k) {
      const double t = x[uni_dim_[k]];
      r += t * (uni_[k][0] + t * (uni_[k][1] + t * uni_[k][2]));
    }
    for (const Cross& c : cross_) {
      double p = c.coefficient;
      for (int f = c.first; f < c.first + c.count; ++f) {
        const auto& fa = factors_[static_cast<std::size_t>(f)];
        for (int e = 0; e < fa[1]; ++e) p *= x[fa[0]];
      }
      r += p;
    }
    return r;
  }

 private:
  struct Cross {
    double coefficient;
    int first, count;
  };
  double constant_ = 0.0;
  std::vector<int> uni_dim_;
  std::vector<char> has_uni_;
  std::vector<std::array<double, 3>> uni_;
  std::vector<Cross> cross_;
  std::vector<std::array<int, 2>> factors_;
};

std::vector<LocalTerm> derivative(const std::vector<LocalTerm>& terms, int dim) {
  std::vector<LocalTerm> out;
  for (const LocalTerm& t : terms)
    for (std::size_t k = 0; k < t.powers.size(); ++k)
      if (t.powers[k][0] == dim) {
        LocalTerm d{t.coefficient * t.powers[k][1], t.powers};
        if (--d.powers[k][1] == 0) d.powers.erase(d.powers.begin() + static_cast<long>(k));
        out.push_back(std::move(d));
      }
  return out;
}

struct Row {
  std::vector<std::pair<int, double>> a;  // search dimension, coefficient
  double b;
};

// The problem shared by both sides, over the search dimensions: the variables the
// polynomial uses (split) and the other variables the constraints name (never split).
struct Search {
  int dims = 0;
  std::vector<int> variable;  // search dimension → variable
  std::vector<char> split;    // may be split (the polynomial uses it)
  std::vector<Row> rows;
  std::vector<Interval> root;
  double tolerance = 0.0;
  long max_boxes = 0;
};

// One side: maximise `f` (the channel or its negation).
struct Side {
  Compiled f;
  std::vector<Compiled> gradient;  // per search dimension
  // The second derivatives that are not identically zero: ∂²f/∂x_d∂x_e for d ≤ e.
  std::vector<Compiled> hessian;
  std::vector<std::array<int, 2>> hessian_at;  // {d, e} of each
};

struct SideResult {
  double upper = -kInf;  // proven (before slack)
  double best = -kInf;   // attained at `witness`
  std::vector<double> witness;
  long boxes = 0;
  bool converged = false;
  bool empty = false;
};

double row_margin(const Row& r, const Interval* box) {
  double s = std::fabs(r.b);
  for (const auto& [d, a] : r.a) s += std::fabs(a) * box[d].mag();
  return kRowMargin * s;
}

// Constraint propagation: shrinks the box to what the rows allow (each bound moved out by
// a rounding margin, so no admissible point is lost). False when the box is infeasible.
bool tighten(const std::vector<Row>& rows, Interval* box) {
  for (int pass = 0; pass < 2; ++pass)
    for (const Row& r : rows) {
      double least = 0.0;
      for (const auto& [d, a] : r.a) least += a > 0 ? a * box[d].lo : a * box[d].hi;
      const double margin = row_margin(r, box);
      if (least > r.b + margin) return false;
      for (const auto& [d, a] : r.a) {
        const double rest = least - (a > 0 ? a * box[d].lo : a * box[d].hi);
        const double limit = (r.b - rest) / a, m = margin / std::fabs(a);
        if (a > 0)
          box[d].hi = std::min(box[d].hi, limit + m);
        else
          box[d].lo = std::max(box[d].lo, limit - m);
        if (box[d].lo > box[d].hi) return false;
      }
    }
  return true;
}

// Whether every point of the box, over the split dimensions, satisfies the row for some
// value of the other (never split, f-independent) dimensions.
bool box_inside(const Search& s, const Row& r, const Interval* box) {
  double most = 0.0;
  for (const auto& [d, a] : r.a)
    most += (a > 0) == static_cast<bool>(s.split[static_cast<std::size_t>(d)]) ? a * box[d].hi
                                                                               : a * box[d].lo;
  return most <= r.b;
}

bool point_admissible(const std::vector<Row>& rows, const double* x) {
  for (const Row& r : rows) {
    double s = 0.0, m = std::fabs(r.b);
    for (const auto& [d, a] : r.a) {
      s += a * x[d];
      m += std::fabs(a * x[d]);
    }
    if (s > r.b + kRowMargin * m) return false;
  }
  return true;
}

// Moves x inside the box until every row holds, spending first the variables whose
// movement costs the objective least per unit of constraint (a greedy one-row LP on the
// local gradient). False when it does not get there.
bool repair(const Search& s, const Side& side, const Interval* box, double* x) {
  std::vector<double> g(static_cast<std::size_t>(s.dims));
  for (int d = 0; d < s.dims; ++d) g[static_cast<std::size_t>(d)] = side.gradient[d].value(x);
  std::vector<std::pair<double, int>> order;
  for (int pass = 0; pass < 3; ++pass) {
    bool changed = false;
    for (const Row& r : s.rows) {
      double excess = -r.b;
      for (const auto& [d, a] : r.a) excess += a * x[d];
      if (excess <= 0) continue;
      changed = true;
      order.clear();
      for (std::size_t k = 0; k < r.a.size(); ++k) {
        const auto [d, a] = r.a[k];
        // Moving x_d by −sign(a) lowers the row by |a| and changes f by −sign(a)·g.
        order.push_back({std::copysign(1.0, a) * g[static_cast<std::size_t>(d)] / std::fabs(a),
                         static_cast<int>(k)});
      }
      std::sort(order.begin(), order.end());
      for (const auto& [cost, k] : order) {
        const auto [d, a] = r.a[static_cast<std::size_t>(k)];
        const double room = a > 0 ? x[d] - box[d].lo : box[d].hi - x[d];
        const double step = std::min(room, excess / std::fabs(a));
        x[d] = a > 0 ? std::max(box[d].lo, x[d] - step) : std::min(box[d].hi, x[d] + step);
        excess -= std::fabs(a) * step;
        if (excess <= 0) break;
      }
    }
    if (!changed) break;
  }
  return point_admissible(s.rows, x);
}

class Maximiser {
 public:
  Maximiser(const Search& s, const Side& side) : s_(s), side_(side) {
    const auto D = static_cast<std::size_t>(s.dims);
    plain_.resize(D);
    dual_.resize(D);
    x_.resize(D);
    shift_.resize(D);
    crossing_.resize(D);
  }

  SideResult run() {
    SideResult out;
    const auto D = static_cast<std::size_t>(s_.dims);
    std::vector<Interval> root = s_.root;
    out.boxes = 1;
    if (!tighten(s_.rows, root.data())) {
      out.empty = true;
      out.converged = true;
      return out;
    }
    best_ = -kInf;
    witness_.assign(D, 0.0);
    std::priority_queue<Node> open;
    long seq = 0;
    auto push = [&](const Interval* box, double parent_upper) {
      const auto [upper, split] = evaluate(box, parent_upper);
      if (upper <= best_ + s_.tolerance) {
        dropped_ = std::max(dropped_, upper);
        return;
      }
      const int slot = allocate();
      std::copy(box, box + D, slab_.begin() + static_cast<long>(slot) * s_.dims);
      open.push({upper, seq++, slot, split});
    };
    push(root.data(), kInf);
    std::vector<Interval> child(D);
    bool budget_hit = false;
    while (!open.empty()) {
      const Node top = open.top();
      if (top.upper <= best_ + s_.tolerance) break;
      if (out.boxes >= s_.max_boxes) {
        budget_hit = true;
        break;
      }
      open.pop();
      const Interval* box = slab_.data() + static_cast<long>(top.slot) * s_.dims;
      if (top.split < 0) {
        unsplittable_ = std::max(unsplittable_, top.upper);
        free_.push_back(top.slot);
        continue;
      }
      const Interval parent = box[top.split];
      const double cut = parent.mid();
      for (int half = 0; half < 2; ++half) {
        box = slab_.data() + static_cast<long>(top.slot) * s_.dims;  // push may grow the slab
        std::copy(box, box + D, child.begin());
        child[static_cast<std::size_t>(top.split)] =
            half == 0 ? Interval{parent.lo, cut} : Interval{cut, parent.hi};
        ++out.boxes;
        if (tighten(s_.rows, child.data())) push(child.data(), top.upper);
      }
      free_.push_back(top.slot);
    }
    out.upper = std::max({open.empty() ? -kInf : open.top().upper, dropped_, unsplittable_});
    out.best = best_;
    out.empty = out.upper == -kInf && best_ == -kInf;
    if (best_ > -kInf) out.witness = witness_;
    out.converged = !budget_hit && (out.empty || out.upper <= best_ + s_.tolerance);
    return out;
  }

 private:
  struct Node {
    double upper;
    long seq;
    int slot, split;
    bool operator<(const Node& o) const { return upper != o.upper ? upper < o.upper : seq > o.seq; }
  };

  int allocate() {
    if (!free_.empty()) {
      const int slot = free_.back();
      free_.pop_back();
      return slot;
    }
    slab_.resize(slab_.size() + static_cast<std::size_t>(s_.dims));
    return static_cast<int>(slab_.size() / static_cast<std::size_t>(s_.dims)) - 1;
  }

  void attain(const double* x) {
    const double v = side_.f.value(x);
    if (v > best_) {
      best_ = v;
      std::copy(x, x + s_.dims, witness_.begin());
    }
  }

  // Scratch for one enclosure: the box reduced by monotonicity, the gradient enclosures,
  // which dimensions were fixed, the reduced box's centre and the Hessian diagonal's upper
  // ends (the Taylor form's).
  struct Reduction {
    std::vector<Interval> box, grad;
    std::vector<char> fixed;
    std::vector<double> centre, curvature;
    void resize(std::size_t D) {
      box.resize(D);
      grad.resize(D);
      fixed.resize(D);
      centre.resize(D);
      curvature.resize(D);
    }
  };

  // Upper bound over the box of L(x) = f(x) + Σ_d shift[d]·x_d + shift0 (shift null: f).
  double upper_bound(const Interval* box, const double* shift, double shift0, Reduction& r) {
    const int D = s_.dims;
    std::copy(box, box + D, r.box.begin());
    std::fill(r.fixed.begin(), r.fixed.end(), 0);
    // Monotonicity: where ∂L/∂x_d has one sign over the (reduced) box, the maximum over
    // the box lies on that face, so the box shrinks to it; repeat while it fixes more.
    for (int round = 0; round < 3; ++round) {
      bool more = false;
      for (int d = 0; d < D; ++d) {
        const auto k = static_cast<std::size_t>(d);
        if (r.fixed[k]) continue;
        if (!s_.split[k]) {
          // f does not depend on it; L does through the shift, with constant slope.
          if (shift && shift[d] != 0.0) {
            r.box[k] = shift[d] > 0 ? Interval{r.box[k].hi, r.box[k].hi}
                                    : Interval{r.box[k].lo, r.box[k].lo};
            r.fixed[k] = 1;
          }
          continue;
        }
        Interval g = side_.gradient[k].enclose(r.box.data());
        if (shift) g = g + Interval{shift[d], shift[d]};
        r.grad[k] = g;
        if (g.lo >= 0 || g.hi <= 0) {
          r.box[k] =
              g.lo >= 0 ? Interval{r.box[k].hi, r.box[k].hi} : Interval{r.box[k].lo, r.box[k].lo};
          r.fixed[k] = 1;
          more = true;
        }
      }
      if (!more) break;
    }
    // Natural enclosure and mean-value form on the reduced box; keep the smaller. Every
    // dimension L varies with is either fixed or in the mean-value sum.
    double upper = side_.f.enclose(r.box.data(), shift).hi + shift0;
    for (int d = 0; d < D; ++d) r.centre[static_cast<std::size_t>(d)] = r.box[d].mid();
    double fm = side_.f.value(r.centre.data()) + shift0;
    if (shift)
      for (int d = 0; d < D; ++d) fm += shift[d] * r.centre[static_cast<std::size_t>(d)];
    Interval mv{0, 0};
    for (int d = 0; d < D; ++d) {
      const auto k = static_cast<std::size_t>(d);
      if (s_.split[k] && !r.fixed[k])
        mv = mv + r.grad[k] * (r.box[k] - Interval{r.centre[k], r.centre[k]});
    }
    // std::min keeps the earlier argument when a later one is NaN: the Taylor form, last,
    // can never replace a bound by NaN.
    return std::min({upper, fm + mv.hi, second_order(r, shift, fm)});
  }

  // The second-order Taylor form on the reduced box: with h = x − m and the Hessian
  // enclosed over the box (Lagrange remainder), L(x) ≤ L(m) + Σ_d (g_d·h_d + H_dd.hi·h_d²/2)
  // + Σ_{d<e} |H_de|·|h_d|·|h_e|, each part maximised over |h| ≤ half-width. Its
  // overestimate near an interior maximum is about half the mean-value form's, and a
  // concave direction can lower it below L(m) + |g|·r. The shift is linear: it moves the
  // gradient, not the Hessian.
  double second_order(Reduction& r, const double* shift, double fm) const {
    const int D = s_.dims;
    std::fill(r.curvature.begin(), r.curvature.end(), 0.0);
    double bound = fm;
    for (std::size_t k = 0; k < side_.hessian.size(); ++k) {
      const auto [d, e] = side_.hessian_at[k];
      if (r.fixed[static_cast<std::size_t>(d)] || r.fixed[static_cast<std::size_t>(e)]) continue;
      const Interval h = side_.hessian[k].enclose(r.box.data());
      if (d == e)
        r.curvature[static_cast<std::size_t>(d)] = h.hi;
      else
        bound += h.mag() * (0.5 * r.box[d].width()) * (0.5 * r.box[e].width());
    }
    for (int d = 0; d < D; ++d) {
      const auto k = static_cast<std::size_t>(d);
      if (!s_.split[k] || r.fixed[k]) continue;
      const double g = side_.gradient[k].value(r.centre.data()) + (shift ? shift[d] : 0.0);
      bound += quadratic_max(g, r.curvature[k], 0.5 * r.box[d].width());
    }
    return bound;
  }

  // A Lagrangian bound: for multipliers λ ≥ 0, max f over box ∩ {A·x ≤ b} ≤ max over the
  // whole box of f − Σ λ_r·(a_r·x − b_r). λ_r comes from the one-row linear programme on
  // f's gradient at the box centre (a fractional knapsack), row by row. Fills shift_ and
  // returns shift0, or NaN when every λ is 0.
  double multipliers(const Interval* box) {
    const int D = s_.dims;
    for (int d = 0; d < D; ++d) x_[static_cast<std::size_t>(d)] = box[d].mid();
    for (int d = 0; d < D; ++d)
      shift_[static_cast<std::size_t>(d)] =
          side_.gradient[static_cast<std::size_t>(d)].value(x_.data());
    std::vector<double>& g = shift_;  // g + shift, built in place: starts as the gradient
    double shift0 = 0.0;
    bool any = false;
    for (const Row& row : s_.rows) {
      if (box_inside(s_, row, box)) continue;
      double excess = -row.b;
      order_.clear();
      for (std::size_t k = 0; k < row.a.size(); ++k) {
        const auto [d, a] = row.a[k];
        const double gd = g[static_cast<std::size_t>(d)];
        const bool at_hi = gd >= 0;  // where the linearised objective is largest
        excess += a * (at_hi ? box[d].hi : box[d].lo);
        // Moving off that end lowers the row only if a has the same sign as the move.
        if ((a > 0) == at_hi) order_.push_back({std::fabs(gd / a), static_cast<int>(k)});
      }
      if (excess <= 0) continue;
      std::sort(order_.begin(), order_.end());
      double lambda = 0.0;
      for (const auto& [cost, k] : order_) {
        const auto [d, a] = row.a[static_cast<std::size_t>(k)];
        lambda = cost;
        excess -= std::fabs(a) * box[d].width();
        if (excess <= 0) break;
      }
      if (lambda <= 0) continue;
      any = true;
      for (const auto& [d, a] : row.a) g[static_cast<std::size_t>(d)] -= lambda * a;
      shift0 += lambda * row.b;
    }
    if (!any) return kNaN;
    // Back from g + shift to the shift alone.
    for (int d = 0; d < D; ++d)
      shift_[static_cast<std::size_t>(d)] -=
          side_.gradient[static_cast<std::size_t>(d)].value(x_.data());
    return shift0;
  }

  bool try_point(const Interval* box, double* x) {
    if (!point_admissible(s_.rows, x) && !repair(s_, side_, box, x)) return false;
    attain(x);
    return true;
  }

  // Upper bound of f over the admissible part of the box and the dimension to split (−1:
  // none helps). Also tries admissible points of the box for the attained value.
  std::pair<double, int> evaluate(const Interval* box, double parent_upper) {
    const int D = s_.dims;
    double upper = std::min(parent_upper, upper_bound(box, nullptr, 0.0, plain_));
    // Whether the face of the box that the bound came from is admissible: then the
    // constraints do not widen the gap here.
    bool inside = true;
    std::fill(crossing_.begin(), crossing_.end(), 0);
    for (const Row& r : s_.rows)
      if (!box_inside(s_, r, plain_.box.data())) {
        inside = false;
        for (const auto& [d, a] : r.a) crossing_[static_cast<std::size_t>(d)] = 1;
      }
    const Reduction* used = &plain_;
    if (!inside && upper > best_ + s_.tolerance) {
      const double shift0 = multipliers(box);
      if (!std::isnan(shift0)) {
        const double lagrangian = upper_bound(box, shift_.data(), shift0, dual_);
        try_point(box, dual_.centre.data());
        if (lagrangian < upper) {
          upper = lagrangian;
          used = &dual_;
        }
      }
    }
    if (!try_point(box, plain_.centre.data()) && inside) {
      // Each row alone admits the bound's face, but together they do not (they share a
      // variable the polynomial does not use): every row counts as cutting it.
      inside = false;
      for (const Row& r : s_.rows)
        for (const auto& [d, a] : r.a) crossing_[static_cast<std::size_t>(d)] = 1;
    }

    // Split rule: the dimension contributing most width (|gradient| · width) to the
    // mean-value enclosure of the reduction that gave the bound (also when the Taylor form
    // gave it: the rule only steers the search). A fixed (monotone) dimension contributes nothing,
    // unless it is in a row that cuts the face the bound came from: then part of the gap is
    // that face's inadmissible corner.
    int split = -1;
    double score = 0.0;
    auto consider = [&](const Reduction& r) {
      for (int d = 0; d < D; ++d) {
        const auto k = static_cast<std::size_t>(d);
        if (!s_.split[k] || box[d].width() <= 0 || (r.fixed[k] && !crossing_[k])) continue;
        const double sc = r.grad[k].mag() * box[d].width();
        if (sc > score) {
          score = sc;
          split = d;
        }
      }
    };
    consider(*used);
    // f is flat here but the box crosses a constraint: cut the widest crossing term of a
    // polynomial variable, and as a last resort of a constraint-only one.
    for (int pass = 0; pass < 2 && split < 0 && !inside; ++pass)
      for (const Row& r : s_.rows)
        for (const auto& [d, a] : r.a) {
          const double sc = std::fabs(a) * box[d].width();
          if (crossing_[static_cast<std::size_t>(d)] &&
              static_cast<bool>(s_.split[static_cast<std::size_t>(d)]) == (pass == 0) &&
              sc > score) {
            score = sc;
            split = d;
          }
        }
    // Stop splitting where halving no longer changes the box in floating point.
    if (split >= 0) {
      const double m = box[split].mid();
      if (!(m > box[split].lo && m < box[split].hi)) split = -1;
    }
    return {upper, split};
  }

  const Search& s_;
  const Side& side_;
  std::vector<Interval> slab_;
  Reduction plain_, dual_;
  std::vector<double> x_, shift_, witness_;
  std::vector<std::pair<double, int>> order_;
  std::vector<char> crossing_;  // in a row that cuts the bound's face
  std::vector<int> free_;
  double best_ = -kInf, dropped_ = -kInf, unsplittable_ = -kInf;
};

Side make_side(const Search& s, const std::vector<LocalTerm>& terms) {
  Side side{Compiled(s.dims, terms), {}, {}, {}};
  for (int d = 0; d < s.dims; ++d) {
    const std::vector<LocalTerm> first = derivative(terms, d);
    side.gradient.emplace_back(s.dims, first);
    for (int e = d; e < s.dims; ++e) {
      std::vector<LocalTerm> second = derivative(first, e);
      std::erase_if(second, [](const LocalTerm& t) { return t.coefficient == 0.0; });
      if (second.empty()) continue;
      side.hessian.emplace_back(s.dims, second);
      side.hessian_at.push_back({d, e});
    }
  }
  return side;
}

}  // namespace

ChannelBound bound_channel(const ChannelPolynomial& p, std::span<const Interval> box,
                           std::span<const LinearInequality> constraints,
                           const BoundOptions& options) {
  const int n = p.variable_count;
  if (static_cast<int>(box.size()) != n)
    throw std::invalid_argument("bound_channel: the box has " + std::to_string(box.size()) +
                                " intervals, the polynomial " + std::to_string(n) + " variables");
  for (int v = 0; v < n; ++v)
    if (!std::isfinite(box[v].lo) || !std::isfinite(box[v].hi) || box[v].lo > box[v].hi)
      throw std::invalid_argument("bound_channel: interval " + std::to_string(v) +
                                  " is empty or not finite");
  if (!(options.tolerance >= 0) || options.max_boxes < 1)
    throw std::invalid_argument("bound_channel: tolerance must be ≥ 0 and max_boxes ≥ 1");

  // Search dimensions: the polynomial's variables, then the others the constraints name.
  std::vector<int> dim_of(static_cast<std::size_t>(n), -1);
  Search s;
  for (int v : p.used_variables()) {
    dim_of[static_cast<std::size_t>(v)] = s.dims++;
    s.variable.push_back(v);
    s.split.push_back(1);
  }
  bool empty = false;
  for (const LinearInequality& c : constraints) {
    if (static_cast<int>(c.a.size()) != n || !std::isfinite(c.b))
      throw std::invalid_argument("bound_channel: a constraint row has " +
                                  std::to_string(c.a.size()) + " coefficients for " +
                                  std::to_string(n) + " variables, or a non-finite bound");
    Row r{{}, c.b};
    for (int v = 0; v < n; ++v) {
      const double a = c.a[static_cast<std::size_t>(v)];
      if (!std::isfinite(a)) throw std::invalid_argument("bound_channel: a non-finite coefficient");
      if (a == 0.0) continue;
      if (dim_of[static_cast<std::size_t>(v)] < 0) {
        dim_of[static_cast<std::size_t>(v)] = s.dims++;
        s.variable.push_back(v);
        s.split.push_back(0);
      }
      r.a.push_back({dim_of[static_cast<std::size_t>(v)], a});
    }
    if (r.a.empty() && r.b < 0) empty = true;  // 0 ≤ b fails for every point
    if (!r.a.empty()) s.rows.push_back(std::move(r));
  }
  for (int v : s.variable) s.root.push_back(box[v]);

  // The rounding slack: M bounds |every term| as the tick evaluates it (docs/VERIFY.md).
  double magnitude = std::fabs(p.constant);
  for (const PolynomialTerm& t : p.terms) {
    double m = t.magnitude;
    for (const auto& [v, e] : t.monomial.powers) m *= std::pow(box[v].mag(), e);
    magnitude += m;
  }
  const double slack = kRelativeSlack * magnitude + kAbsoluteSlack;
  s.tolerance = options.tolerance > 2 * slack ? options.tolerance - slack : options.tolerance / 2;
  s.max_boxes = options.max_boxes;

  std::vector<LocalTerm> plus, minus;
  for (const PolynomialTerm& t : p.terms) {
    if (t.monomial.coefficient == 0.0) continue;
    Powers powers;
    for (const auto& [v, e] : t.monomial.powers)
      powers.push_back({dim_of[static_cast<std::size_t>(v)], e});
    plus.push_back({t.monomial.coefficient, powers});
    minus.push_back({-t.monomial.coefficient, std::move(powers)});
  }
  plus.push_back({p.constant, {}});
  minus.push_back({-p.constant, {}});

  ChannelBound out;
  auto full_witness = [&](const std::vector<double>& local) {
    std::vector<double> x(static_cast<std::size_t>(n));
    for (int v = 0; v < n; ++v) x[static_cast<std::size_t>(v)] = box[v].mid();
    for (int d = 0; d < s.dims; ++d) x[static_cast<std::size_t>(s.variable[d])] = local[d];
    return x;
  };
  if (empty) {
    out = {kInf, -kInf, kNaN, kNaN, {}, {}, 0, true, true};
    return out;
  }
  const SideResult hi = Maximiser(s, make_side(s, plus)).run();
  const SideResult lo = Maximiser(s, make_side(s, minus)).run();
  out.boxes_used = hi.boxes + lo.boxes;
  if (hi.empty || lo.empty) {
    out.lower = kInf;
    out.upper = -kInf;
    out.attained_min = out.attained_max = kNaN;
    out.empty = out.converged = true;
    out.boxes_used = hi.boxes + lo.boxes;
    return out;
  }
  out.upper = hi.upper + slack;
  out.lower = -lo.upper - slack;
  out.attained_max = hi.best > -kInf ? hi.best : kNaN;
  out.attained_min = lo.best > -kInf ? -lo.best : kNaN;
  if (!hi.witness.empty()) out.witness_max = full_witness(hi.witness);
  if (!lo.witness.empty()) out.witness_min = full_witness(lo.witness);
  out.converged = hi.converged && lo.converged;
  return out;
}

}  // namespace facectl::verify
