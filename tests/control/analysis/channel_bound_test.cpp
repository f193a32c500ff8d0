// The control-point channel bound of `facectl verify`: exact on hand-checkable
// polynomials, sound on the shipped reduced model (every sampled admissible input lands
// inside the proven range), tight to its tolerance when it says it converged, and an
// empty admissible set is reported as such.
#include "control/analysis/channel_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "control/analysis/channel_polynomial.hpp"
#include "tests/support/default_face_space.hpp"
#include "tests/support/sample_count.hpp"

namespace facectl::verify {
namespace {

// A polynomial over `count` variables from {coefficient, {{variable, power}...}} terms.
ChannelPolynomial polynomial(int count, double constant,
                             std::vector<std::pair<double, face::Monomial>> terms) {
  ChannelPolynomial p;
  p.variable_count = count;
  p.constant = constant;
  for (auto& [c, m] : terms) {
    m.coefficient = c;
    p.terms.push_back({m, std::fabs(c)});
  }
  return p;
}

LinearInequality row(int count, std::vector<std::pair<int, double>> a, double b) {
  LinearInequality r{std::vector<double>(static_cast<std::size_t>(count), 0.0), b};
  for (auto [v, c] : a) r.a[static_cast<std::size_t>(v)] = c;
  return r;
}

// q = 0.25 + x0³ − x0 + 2·x1·x2 − x1², x0 ∈ [−1, 2], x1 ∈ [−1, 1], x2 ∈ [0, 2].
// x0³ − x0 spans [−2/(3√3), 6]; 2·x1·x2 − x1² spans [−5, 3] (x2 = 2, x1 = −1 and 1).
ChannelPolynomial hand_checked() {
  return polynomial(3, 0.25,
                    {{1.0, {1, {{0, 3}}}},
                     {-1.0, {1, {{0, 1}}}},
                     {2.0, {1, {{1, 1}, {2, 1}}}},
                     {-1.0, {1, {{1, 2}}}}});
}
const std::vector<Interval> kHandCheckedBox{{-1, 2}, {-1, 1}, {0, 2}};

TEST(ChannelBound, HandCheckedCubicWithCrossTerm) {
  const ChannelBound b = bound_channel(hand_checked(), kHandCheckedBox, {}, {1e-9, 100000});
  const double lo = 0.25 - 2 / (3 * std::sqrt(3.0)) - 5, hi = 0.25 + 6 + 3;
  // Within the tolerance plus the rounding slack (1e-10 of Σ|terms| ≈ 14).
  const double slack = kRelativeSlack * (0.25 + 8 + 1 + 4 + 1) + kAbsoluteSlack;
  ASSERT_TRUE(b.converged);
  EXPECT_LE(b.lower, lo);
  EXPECT_GE(b.upper, hi);
  EXPECT_NEAR(b.lower, lo, 1e-9 + slack);
  EXPECT_NEAR(b.upper, hi, 1e-9 + slack);
  EXPECT_NEAR(b.attained_min, lo, 1e-9);
  EXPECT_DOUBLE_EQ(b.attained_max, hi);
  EXPECT_EQ(b.witness_max, (std::vector<double>{2, 1, 2}));
  EXPECT_NEAR(b.witness_min[0], 1 / std::sqrt(3.0), 1e-4);  // the cubic's interior minimum
  EXPECT_EQ(b.witness_min[1], -1);
  EXPECT_EQ(b.witness_min[2], 2);
}

TEST(ChannelBound, ConstraintCutsTheCorner) {
  // q = 3·x0 + x1 on [0, 1]² with x0 + x1 ≤ 1.5: the maximum 3.5 is at (1, 0.5), inside an
  // edge of the box, not at a corner; the minimum 0 at the origin.
  const ChannelPolynomial p = polynomial(2, 0, {{3.0, {1, {{0, 1}}}}, {1.0, {1, {{1, 1}}}}});
  const std::vector<Interval> box{{0, 1}, {0, 1}};
  const std::vector<LinearInequality> rows{row(2, {{0, 1}, {1, 1}}, 1.5)};
  const ChannelBound b = bound_channel(p, box, rows, {1e-9, 100000});
  ASSERT_TRUE(b.converged);
  EXPECT_NEAR(b.upper, 3.5, 2e-9);
  EXPECT_GE(b.upper, 3.5);
  EXPECT_NEAR(b.lower, 0, 2e-9);
  EXPECT_LE(b.lower, 0);
  EXPECT_LE(b.witness_max[0] + b.witness_max[1], 1.5 + 1e-12);
}

TEST(ChannelBound, ConstraintOnAnotherVariablePrunesWithoutSplittingIt) {
  // q = x0 with x0 + x1 ≤ 1 and x1 ≥ 0.25: x0 ≤ 0.75 although q ignores x1.
  const ChannelPolynomial p = polynomial(2, 0, {{1.0, {1, {{0, 1}}}}});
  const std::vector<Interval> box{{0, 1}, {0, 1}};
  const std::vector<LinearInequality> rows{row(2, {{0, 1}, {1, 1}}, 1), row(2, {{1, -1}}, -0.25)};
  const ChannelBound b = bound_channel(p, box, rows, {1e-9, 100000});
  ASSERT_TRUE(b.converged);
  EXPECT_NEAR(b.upper, 0.75, 2e-9);
  EXPECT_NEAR(b.attained_max, 0.75, 1e-9);
  EXPECT_GE(b.witness_max[1], 0.25);
}

TEST(ChannelBound, RowsCoupledThroughAnUnusedVariable) {
  // q = x0 − x2 with x0 ≤ x1, x0 + x1 ≤ 1 and x1 − x2 ≤ 0.25. q ignores x1, which the rows
  // tie to both: x2 ≥ x1 − 0.25 ≥ x0 − 0.25, so q ≤ 0.25 (at x0 = x1 = t, x2 = t − 0.25 for
  // any t in [0.25, 0.5]), although each row alone allows q = 1.
  const ChannelPolynomial p = polynomial(3, 0, {{1.0, {1, {{0, 1}}}}, {-1.0, {1, {{2, 1}}}}});
  const std::vector<Interval> box{{0, 1}, {0, 1}, {0, 1}};
  const std::vector<LinearInequality> rows{
      row(3, {{0, 1}, {1, -1}}, 0), row(3, {{0, 1}, {1, 1}}, 1), row(3, {{1, 1}, {2, -1}}, 0.25)};
  // The maximum is attained along a segment, where the gap closes only linearly in the
  // box width: the default tolerance.
  const ChannelBound b = bound_channel(p, box, rows);
  ASSERT_TRUE(b.converged) << b.lower << " " << b.upper << " " << b.attained_min << " "
                           << b.attained_max << " " << b.boxes_used;
  EXPECT_GE(b.upper, 0.25);
  EXPECT_NEAR(b.upper, 0.25, 1e-6);
  EXPECT_NEAR(b.lower, -1, 1e-6);
  const std::vector<double>& w = b.witness_max;
  EXPECT_NEAR(w[0] - w[2], 0.25, 1e-6);
  EXPECT_LE(w[0], w[1] + 1e-12);
  EXPECT_LE(w[0] + w[1], 1 + 1e-12);
  EXPECT_LE(w[1] - w[2], 0.25 + 1e-12);
}

TEST(ChannelBound, EmptyAdmissibleSetIsReported) {
  const ChannelPolynomial p = polynomial(2, 0, {{1.0, {1, {{0, 1}, {1, 1}}}}});
  const std::vector<Interval> box{{0, 1}, {0, 1}};
  // x0 + x1 ≥ 1.5 and x0 + x1 ≤ 1.2 cannot both hold.
  const std::vector<LinearInequality> rows{row(2, {{0, -1}, {1, -1}}, -1.5),
                                           row(2, {{0, 1}, {1, 1}}, 1.2)};
  const ChannelBound b = bound_channel(p, box, rows);
  EXPECT_TRUE(b.empty);
  EXPECT_GT(b.lower, b.upper);
  EXPECT_TRUE(std::isnan(b.attained_max));
  EXPECT_TRUE(b.witness_max.empty());
  // A row with no variable that fails (0 ≤ −1) empties the set too.
  EXPECT_TRUE(bound_channel(p, box, std::vector{row(2, {}, -1)}).empty);
}

TEST(ChannelBound, AnInteriorMaximumInSixVariablesTakesFewBoxes) {
  // q = Σ_i (2·a_i·x_i − x_i²) + 0.1·Σ_{i<j} x_i·x_j on [0, 1]⁶: concave, its maximum
  // inside the box where −2·x_i + 2·a_i + 0.1·Σ_{j≠i} x_j = 0. The mean-value form's
  // overestimate near such a maximum is twice the second-order Taylor form's in every
  // pair of variables: the search takes 3106 boxes with the Taylor form, 89 796 without.
  constexpr int n = 6;
  const double a[n] = {0.3, 0.45, 0.5, 0.35, 0.6, 0.4};
  std::vector<std::pair<double, face::Monomial>> terms;
  for (int i = 0; i < n; ++i) {
    terms.push_back({2 * a[i], {1, {{i, 1}}}});
    terms.push_back({-1.0, {1, {{i, 2}}}});
    for (int j = i + 1; j < n; ++j) terms.push_back({0.1, {1, {{i, 1}, {j, 1}}}});
  }
  const ChannelPolynomial p = polynomial(n, 0, terms);
  double x[n] = {};
  for (int it = 0; it < 200; ++it)  // Gauss–Seidel on the stationarity conditions
    for (int i = 0; i < n; ++i) {
      double rest = 0;
      for (int j = 0; j < n; ++j) rest += j == i ? 0 : x[j];
      x[i] = a[i] + 0.05 * rest;
    }
  const double top = p.evaluate(std::vector<double>(x, x + n));
  const ChannelBound b = bound_channel(p, std::vector<Interval>(n, {0, 1}), {}, {1e-9, 100000});
  ASSERT_TRUE(b.converged);
  EXPECT_GE(b.upper, top);
  EXPECT_NEAR(b.upper, top, 2e-9);
  for (int i = 0; i < n; ++i) EXPECT_NEAR(b.witness_max[static_cast<std::size_t>(i)], x[i], 1e-3);
  EXPECT_LE(b.boxes_used, 10000);
}

TEST(ChannelBound, RandomCubicsStayInsideTheirBounds) {
  // Random cubics in four variables (every monomial of degree ≤ 3, coefficients of both
  // signs, so curvature changes sign inside the box), on random boxes, half of them under a
  // random coupled limit: no sampled admissible point or corner lies outside the bound.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr int n = 4;
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<std::pair<double, face::Monomial>> terms;
    for (int a = 0; a < n; ++a)
      for (int b = a; b <= n; ++b)
        for (int c = b; c <= n; ++c) {  // index n: no factor
          face::Monomial m{1, {}};
          for (int v : {a, b, c})
            if (v < n) {
              if (!m.powers.empty() && m.powers.back()[0] == v)
                ++m.powers.back()[1];
              else
                m.powers.push_back({v, 1});
            }
          terms.push_back({u(rng), m});
        }
    const ChannelPolynomial p = polynomial(n, u(rng), terms);
    std::vector<Interval> box;
    for (int v = 0; v < n; ++v) {
      const double lo = u(rng);
      box.push_back({lo, lo + 0.2 + std::fabs(u(rng))});
    }
    std::vector<LinearInequality> rows;
    if (trial % 2 == 1) {  // Σ a_v·x_v ≤ its value at the box centre: cuts the box in two
      LinearInequality r{std::vector<double>(n), 0};
      for (int v = 0; v < n; ++v) {
        r.a[static_cast<std::size_t>(v)] = u(rng);
        r.b += r.a[static_cast<std::size_t>(v)] * box[static_cast<std::size_t>(v)].mid();
      }
      rows.push_back(r);
    }
    const ChannelBound b = bound_channel(p, box, rows, {1e-9, 200000});
    ASSERT_TRUE(b.converged) << trial;
    std::vector<double> x(n);
    for (int s = 0; s < 20000; ++s) {
      for (int v = 0; v < n; ++v) {
        const Interval& i = box[static_cast<std::size_t>(v)];
        const double t = s < 16 ? ((s >> v) & 1) : 0.5 + 0.5 * u(rng);  // corners first
        x[static_cast<std::size_t>(v)] = i.lo + t * i.width();
      }
      if (!rows.empty()) {
        double lhs = 0;
        for (int v = 0; v < n; ++v)
          lhs += rows[0].a[static_cast<std::size_t>(v)] * x[static_cast<std::size_t>(v)];
        if (lhs > rows[0].b) continue;
      }
      const double q = p.evaluate(x);
      ASSERT_LE(q, b.upper) << trial;
      ASSERT_GE(q, b.lower) << trial;
    }
  }
}

TEST(ChannelBound, BudgetExhaustedStillGivesAProvenBound) {
  const ChannelBound b = bound_channel(hand_checked(), kHandCheckedBox, {}, {0.0, 3});
  EXPECT_FALSE(b.converged);
  EXPECT_LE(b.lower, 0.25 - 2 / (3 * std::sqrt(3.0)) - 5);
  EXPECT_GE(b.upper, 9.25);
  EXPECT_LE(b.boxes_used, 6);
}

TEST(ChannelBound, RejectsMalformedInput) {
  const ChannelPolynomial p = polynomial(2, 0, {{1.0, {1, {{0, 1}}}}});
  const std::vector<Interval> good{{0, 1}, {0, 1}}, short_box{{0, 1}}, reversed{{1, 0}, {0, 1}};
  EXPECT_THROW(bound_channel(p, short_box, {}), std::invalid_argument);
  EXPECT_THROW(bound_channel(p, reversed, {}), std::invalid_argument);
  EXPECT_THROW(bound_channel(p, good, std::vector{LinearInequality{{1.0}, 1.0}}),
               std::invalid_argument);
}

// ---- The shipped reduced model -------------------------------------------------------

using testing::DefaultFaceSpace;
const DefaultFaceSpace& shipped() {
  return testing::default_face_space();
}

struct Case {
  std::string name;
  ChannelTerms terms;
};

std::vector<Case> channels() {
  const DefaultFaceSpace& s = shipped();
  const int n = s.n;
  const double r2 = std::sqrt(0.5);
  const int c83 = s.point("fdp_8_3"), c84 = s.point("fdp_8_4"), c41 = s.point("fdp_4_1"),
            c82 = s.point("fdp_8_2");
  return {
      {"lip corner 8.3 +y", {0, {{c83, {0, 1, 0}, 1}}, {}}},
      {"lip corner 8.3 +x", {0, {{c83, {1, 0, 0}, 1}}, {}}},
      {"lip corner 8.3 -x", {0, {{c83, {-1, 0, 0}, 1}}, {}}},
      {"lip corner 8.4 +y", {0, {{c84, {0, 1, 0}, 1}}, {}}},
      {"lip corner 8.4 -x", {0, {{c84, {-1, 0, 0}, 1}}, {}}},
      {"brow 4.1 +y", {0, {{c41, {0, 1, 0}, 1}}, {}}},
      {"mixed: both corners, zygomaticus, pitch",
       {0.003,
        {{c83, {0, 1, 0}, 0.5}, {c84, {0, 1, 0}, 0.5}},
        {{s.muscle("zygomaticus_major_l"), 0.01}, {n, -0.02}}}},
      {"mixed: diagonal corner, brow, protrusion, yaw",
       {-0.01,
        {{c83, {r2, r2, 0}, 2.0}, {c41, {0, -1, 0}, 0.7}},
        {{n + 2, 0.3}, {n + 1, 0.01}, {s.muscle("depressor_anguli_oris_l"), -0.004}}}},
      {"mixed: lower lip with jaw pitch", {0, {{c82, {0, -1, 0}, 1}}, {{n, 0.05}}}},
  };
}

std::vector<LinearInequality> coupled_limits() {
  return shipped().coupled_limits();
}

bool admissible(const std::vector<double>& x, std::span<const LinearInequality> rows) {
  const DefaultFaceSpace& s = shipped();
  for (std::size_t v = 0; v < x.size(); ++v)
    if (!s.box[v].contains(x[v])) return false;
  for (const LinearInequality& r : rows) {
    double a = 0;
    for (std::size_t v = 0; v < x.size(); ++v) a += r.a[v] * x[v];
    if (a > r.b + 1e-12) return false;
  }
  return true;
}

// q as the tick computes it: the reduced model's evaluate(), then the channel formula. The
// model is cut down to the channel's control points (same rows, same arithmetic) so that
// millions of samples stay quick.
class TickChannel {
 public:
  explicit TickChannel(const ChannelTerms& t) : terms_(t), model_(shipped().model) {
    model_.coefficients.resize(3 * static_cast<Eigen::Index>(t.points.size()),
                               shipped().model.coefficients.cols());
    for (std::size_t k = 0; k < t.points.size(); ++k) {
      model_.coefficients.middleRows(3 * static_cast<Eigen::Index>(k), 3) =
          shipped().model.coefficients.middleRows(3 * t.points[k].control_point, 3);
      terms_.points[k].control_point = static_cast<int>(k);
    }
    w_ = face::make_reduced_workspace(model_);
    out_.resize(3 * t.points.size());
  }
  double operator()(const std::vector<double>& x) {
    const auto n = static_cast<std::size_t>(shipped().n);
    face::ReducedInput in{std::span<const double>(x).first(n), x[n], x[n + 1], x[n + 2]};
    in.eyelid_closure[0] = x[n + 3];
    in.eyelid_closure[1] = x[n + 4];
    face::evaluate(model_, w_, in, out_);
    double q = terms_.offset;
    for (const ControlPointTerm& p : terms_.points) {
      const auto k = static_cast<std::size_t>(3 * p.control_point);
      q += p.gain * (out_[k] * p.axis[0] + out_[k + 1] * p.axis[1] + out_[k + 2] * p.axis[2]);
    }
    for (const LinearTerm& l : terms_.linear) q += l.gain * x[static_cast<std::size_t>(l.variable)];
    return q;
  }

 private:
  ChannelTerms terms_;
  face::ReducedFaceModel model_;
  face::ReducedFaceWorkspace w_;
  std::vector<double> out_;
};

// Samples admissible points: each coordinate at its lower end, its upper end or uniform
// inside (a third each), so faces and corners of the box are visited often.
class AdmissibleSampler {
 public:
  AdmissibleSampler(std::span<const LinearInequality> rows, unsigned seed)
      : rows_(rows), rng_(seed) {}
  std::vector<double> next() {
    const DefaultFaceSpace& s = shipped();
    std::vector<double> x(s.box.size());
    do {
      for (std::size_t v = 0; v < x.size(); ++v) {
        const int pick = static_cast<int>(rng_() % 3);
        x[v] = pick == 0   ? s.box[v].lo
               : pick == 1 ? s.box[v].hi
                           : s.box[v].lo + u_(rng_) * s.box[v].width();
      }
    } while (!admissible(x, rows_));
    return x;
  }

 private:
  std::span<const LinearInequality> rows_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> u_{0.0, 1.0};
};

// One channel under test: its proof and the range the samples have reached.
struct Proven {
  const Case* c;
  ChannelPolynomial p;
  ChannelBound b;
  TickChannel q;
  double seen_lo = INFINITY, seen_hi = -INFINITY;
  // False (and a test failure) when q(x) leaves the proven range.
  bool check(const std::vector<double>& x) {
    const double v = q(x);
    seen_lo = std::min(seen_lo, v);
    seen_hi = std::max(seen_hi, v);
    if (v >= b.lower && v <= b.upper) return true;
    ADD_FAILURE() << c->name << ": q = " << v << " outside [" << b.lower << ", " << b.upper << "]";
    return false;
  }
};

// Proves every channel, checks tightness and witnesses, then checks every admissible
// corner of the box over each channel's variables (others at their lower end) and
// `samples` random admissible points, shared by all channels, against the proven ranges.
void check_sound_and_tight(std::span<const LinearInequality> rows, int samples) {
  const DefaultFaceSpace& s = shipped();
  // Tight to 1 µm: the mixed brow channel under coupled limits takes about 58 000 boxes
  // (both sides; docs/VERIFY.md); the budget leaves room for a model that needs more.
  BoundOptions opt;
  opt.max_boxes = 1000000;
  std::vector<Case> cases = channels();
  std::vector<Proven> proven;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    ChannelPolynomial p = make_channel_polynomial(s.model, c.terms);
    ChannelBound b = bound_channel(p, s.box, rows, opt);
    ASSERT_FALSE(b.empty);
    ASSERT_TRUE(b.converged) << "boxes " << b.boxes_used;
    EXPECT_LE(b.upper - b.attained_max, opt.tolerance);
    EXPECT_LE(b.attained_min - b.lower, opt.tolerance);
    EXPECT_LE(b.lower, b.attained_min);
    EXPECT_GE(b.upper, b.attained_max);
    TickChannel q(c.terms);
    // The witnesses are admissible and give the attained values.
    ASSERT_TRUE(admissible(b.witness_max, rows));
    ASSERT_TRUE(admissible(b.witness_min, rows));
    EXPECT_NEAR(q(b.witness_max), b.attained_max, 1e-12);
    EXPECT_NEAR(q(b.witness_min), b.attained_min, 1e-12);

    const std::vector<int> used = p.used_variables();
    ASSERT_LE(used.size(), 22u);
    Proven pr{&c, std::move(p), std::move(b), std::move(q)};
    std::vector<double> x(s.box.size());
    for (std::size_t v = 0; v < x.size(); ++v) x[v] = s.box[v].lo;
    for (unsigned long mask = 0; mask < (1ul << used.size()); ++mask) {
      for (std::size_t k = 0; k < used.size(); ++k) {
        const auto v = static_cast<std::size_t>(used[k]);
        x[v] = (mask >> k) & 1 ? s.box[v].hi : s.box[v].lo;
      }
      if (admissible(x, rows)) {
        ASSERT_TRUE(pr.check(x));
      }
    }
    proven.push_back(std::move(pr));
  }
  AdmissibleSampler sampler(rows, 12345);
  for (int k = 0; k < samples; ++k) {
    const std::vector<double> x = sampler.next();
    for (Proven& pr : proven) ASSERT_TRUE(pr.check(x));
  }
  for (const Proven& pr : proven)
    std::printf("  %-46s %s proven [% .6f, % .6f] mm, sampled [% .6f, % .6f] mm, %ld boxes\n",
                pr.c->name.c_str(), rows.empty() ? "free   " : "coupled", 1e3 * pr.b.lower,
                1e3 * pr.b.upper, 1e3 * pr.seen_lo, 1e3 * pr.seen_hi, pr.b.boxes_used);
}

const int kSamples = static_cast<int>(testing::sample_count(1'000'000));

TEST(ChannelBoundShippedModel, SoundAndTightOnTheBox) {
  check_sound_and_tight({}, kSamples);
}

TEST(ChannelBoundShippedModel, SoundAndTightWithCoupledLimits) {
  check_sound_and_tight(coupled_limits(), kSamples);
}

TEST(ChannelBoundShippedModel, CoupledLimitsOnlyNarrowTheRange) {
  const DefaultFaceSpace& s = shipped();
  const std::vector<LinearInequality> rows = coupled_limits();
  for (const Case& c : channels()) {
    const ChannelPolynomial p = make_channel_polynomial(s.model, c.terms);
    const ChannelBound free = bound_channel(p, s.box, {}), cut = bound_channel(p, s.box, rows);
    // Each is within the tolerance of its true extreme.
    EXPECT_LE(cut.upper, free.upper + BoundOptions{}.tolerance) << c.name;
    EXPECT_GE(cut.lower, free.lower - BoundOptions{}.tolerance) << c.name;
  }
}

TEST(ChannelBoundShippedModel, Deterministic) {
  const DefaultFaceSpace& s = shipped();
  const ChannelPolynomial p = make_channel_polynomial(s.model, channels()[6].terms);
  const ChannelBound a = bound_channel(p, s.box, coupled_limits()),
                     b = bound_channel(p, s.box, coupled_limits());
  EXPECT_EQ(a.upper, b.upper);
  EXPECT_EQ(a.lower, b.lower);
  EXPECT_EQ(a.witness_max, b.witness_max);
  EXPECT_EQ(a.boxes_used, b.boxes_used);
}

TEST(ChannelPolynomial, MatchesTheModelAndRejectsBadTerms) {
  const DefaultFaceSpace& s = shipped();
  const Case c = channels()[7];
  const ChannelPolynomial p = make_channel_polynomial(s.model, c.terms);
  TickChannel q(c.terms);
  AdmissibleSampler sampler({}, 7);
  for (int k = 0; k < 1000; ++k) {
    const std::vector<double> x = sampler.next();
    EXPECT_NEAR(p.evaluate(x), q(x), 1e-13);
  }
  ChannelTerms bad;
  bad.points = {{0, {1, 1, 0}, 1}};
  EXPECT_THROW(make_channel_polynomial(s.model, bad), std::invalid_argument);
  bad.points = {{99, {1, 0, 0}, 1}};
  EXPECT_THROW(make_channel_polynomial(s.model, bad), std::invalid_argument);
  bad.points = {};
  bad.linear = {{s.n + 5, 1}};
  EXPECT_THROW(make_channel_polynomial(s.model, bad), std::invalid_argument);
}

}  // namespace
}  // namespace facectl::verify
