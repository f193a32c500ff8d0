// The mandible mechanism's tick-side functions allocate nothing: counted with the
// process-wide allocation counter.
#include <gtest/gtest.h>

#include <numbers>

#include "control/mapping/mandible_mechanism.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/mandible_mechanisms.hpp"

namespace facectl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Runs solve() over reachable and unreachable targets; returns allocations seen.
long allocations_while_solving(const MandibleMechanism& m, double& checksum, int& clamped) {
  MandibleStrokes out{};
  testing::begin_counting_allocations();
  for (int i = 0; i < 2000; ++i) {
    const double t = i / 2000.0;
    // Sweeps from inside the envelope to far outside it.
    const face::MandiblePose target{(-10 + 40 * t) * kDeg, (12 * t - 6) * kDeg,
                                    (16 * t - 4) * 1e-3};
    const MandibleSolveResult r = solve(m, target, out);
    strokes(m, r.achieved, out);
    checksum += out[0] + r.distance;
    clamped += r.clamped ? 1 : 0;
  }
  return testing::end_counting_allocations();
}

TEST(NoAllocation, MandibleMechanismSolve) {
  for (std::size_t n : {3u, 2u}) {
    // Narrow limits, so that most targets are clamped.
    const MandibleMechanism base = testing::proposed_mechanism(n);
    std::array<MandibleStrut, 3> struts = base.strut;
    for (std::size_t i = 0; i < n; ++i)
      struts[i].stroke = {struts[i].stroke_at_rest - 0.005, struts[i].stroke_at_rest + 0.005};
    const MandibleMechanism m =
        make_mandible_mechanism(base.axes, std::span(base.dof.data(), n),
                                std::span(struts.data(), n), MandibleEnvelope::design_default());
    double checksum = 0.0;
    int clamped = 0;
    EXPECT_EQ(allocations_while_solving(m, checksum, clamped), 0) << n << " struts";
    EXPECT_GT(checksum, 0.0);
    EXPECT_GT(clamped, 1000);  // most of the sweep is clamped
  }
}

}  // namespace
}  // namespace facectl
