// The mandible mechanism's range proof is sound (no admissible pose has a stroke
// outside the proven enclosure, over a million random poses and the corners),
// tight (attained within the tolerance of the bound, at admissible witnesses),
// and decides reachability with a witness.
#include "control/analysis/mechanism_range_proof.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "tests/support/mandible_mechanisms.hpp"
#include "tests/support/sample_count.hpp"

namespace facectl {
namespace {

using testing::proposed_mechanism;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kTolerance = 1e-6;
// The proof's own rounding allowance may add to the gap.
constexpr double kGap = kTolerance + 2e-9;

const MandibleEnvelope kEnvelope = MandibleEnvelope::design_default();

// The default rig's yaw band: |yaw| <= 3° + 0.25·pitch.
const std::array<MandibleLinearConstraint, 2> kYawBand = {
    MandibleLinearConstraint{{-0.25, 1.0, 0.0}, 3 * kDeg},
    MandibleLinearConstraint{{-0.25, -1.0, 0.0}, 3 * kDeg}};

bool admissible(const MandibleVector& q, std::span<const MandibleLinearConstraint> cs) {
  for (const auto& c : cs)
    if (c.a.dot(q) > c.b) return false;
  return true;
}

// A tenth when sanitized: the corners, where the extremes lie, are always drawn.
const int kSamples = static_cast<int>(testing::sample_count(1'000'000));

// Samples `count` uniform poses of the envelope plus its 8 corners; checks that
// every admissible one's strokes lie in the proven enclosure and returns the
// sampled extremes per strut.
std::array<Range, 3> check_samples(const MandibleMechanism& m, const MechanismRangeProof& proof,
                                   std::span<const MandibleLinearConstraint> cs, int count,
                                   std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::array<Range, 3> seen;
  for (Range& r : seen) r = {1e9, -1e9};
  const std::array<Range, 3> box = {kEnvelope.pitch, kEnvelope.yaw, kEnvelope.protrusion};
  long outside = 0, checked = 0;
  for (int n = -8; n < count; ++n) {
    MandibleVector q;
    for (int k = 0; k < 3; ++k) {
      const double t = n < 0 ? static_cast<double>(((n + 8) >> k) & 1) : u(rng);
      q[k] = box[k].min + t * (box[k].max - box[k].min);
    }
    q = m.held_in(q);
    if (!admissible(q, cs)) continue;
    ++checked;
    MandibleStrokes s{};
    strokes(m, to_pose(q), s);
    for (std::size_t i = 0; i < m.count; ++i) {
      const Range& p = proof.strut[i].proven;
      if (s[i] < p.min || s[i] > p.max) ++outside;
      seen[i].min = std::min(seen[i].min, s[i]);
      seen[i].max = std::max(seen[i].max, s[i]);
    }
  }
  EXPECT_EQ(outside, 0) << "strokes outside the proven enclosure";
  EXPECT_GT(checked, count / 2);
  return seen;
}

void expect_tight(const MandibleMechanism& m, const MechanismRangeProof& proof,
                  std::span<const MandibleLinearConstraint> cs) {
  for (std::size_t i = 0; i < m.count; ++i) {
    const StrokeEnclosure& e = proof.strut[i];
    EXPECT_TRUE(e.converged) << i;
    EXPECT_LE(e.proven.min, e.attained.min);
    EXPECT_GE(e.proven.max, e.attained.max);
    EXPECT_LE(e.attained.min - e.proven.min, kGap) << i;
    EXPECT_LE(e.proven.max - e.attained.max, kGap) << i;
    // The witnesses are admissible and attain what the proof says.
    for (const auto& [pose, value] :
         {std::pair{e.argmin, e.attained.min}, std::pair{e.argmax, e.attained.max}}) {
      const MandibleVector q = to_vector(pose);
      EXPECT_TRUE(admissible(q, cs));
      EXPECT_GE(q[0], kEnvelope.pitch.min);
      EXPECT_LE(q[0], kEnvelope.pitch.max);
      MandibleStrokes s{};
      strokes(m, pose, s);
      EXPECT_NEAR(s[i], value, 1e-12);
    }
  }
}

TEST(MechanismRangeProof, SoundAndTightForTheDefaultMechanism) {
  const MandibleMechanism m = proposed_mechanism(3);
  const MechanismRangeProof proof = prove_stroke_ranges(m, kEnvelope);
  ASSERT_FALSE(proof.empty);
  EXPECT_EQ(proof.reach, MechanismReach::kProven);
  expect_tight(m, proof, {});
  const auto seen = check_samples(m, proof, {}, kSamples, 7);
  // The samples come close to the bound, from inside.
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT(proof.strut[i].proven.max - seen[i].max, 1e-3) << i;
    EXPECT_LT(seen[i].min - proof.strut[i].proven.min, 1e-3) << i;
  }
}

TEST(MechanismRangeProof, SoundAndTightForTheTwoStrutMechanism) {
  const MandibleMechanism m = proposed_mechanism(2);
  const MechanismRangeProof proof = prove_stroke_ranges(m, kEnvelope);
  EXPECT_EQ(proof.reach, MechanismReach::kProven);
  expect_tight(m, proof, {});
  check_samples(m, proof, {}, kSamples, 8);
  // Protrusion is held at 0, whatever the envelope allows.
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(proof.strut[i].argmax.protrusion_m, 0.0);
    EXPECT_EQ(proof.strut[i].argmin.protrusion_m, 0.0);
  }
}

TEST(MechanismRangeProof, ConstraintsPruneSoundly) {
  const MandibleMechanism m = proposed_mechanism(3);
  const MechanismRangeProof free = prove_stroke_ranges(m, kEnvelope);
  const MechanismRangeProof banded = prove_stroke_ranges(m, kEnvelope, kYawBand);
  expect_tight(m, banded, kYawBand);
  check_samples(m, banded, kYawBand, kSamples, 9);
  // Yaw is narrower at small pitch, so the pterygoid struts (yaw ≈ their
  // difference) see a narrower range.
  for (std::size_t i = 1; i < 3; ++i) {
    const double free_span = free.strut[i].proven.max - free.strut[i].proven.min;
    const double banded_span = banded.strut[i].proven.max - banded.strut[i].proven.min;
    EXPECT_LT(banded_span, free_span - 1e-4) << i;
  }
}

TEST(MechanismRangeProof, ReportsAViolationWithAWitness) {
  const MandibleMechanism base = proposed_mechanism(3);
  std::array<MandibleStrut, 3> struts = base.strut;
  struts[0].stroke.min = 0.010;  // the digastric cannot open the jaw all the way
  const std::array<MandibleDof, 3> dofs = {MandibleDof::kPitch, MandibleDof::kYaw,
                                           MandibleDof::kProtrusion};
  const MandibleMechanism m = make_mandible_mechanism(base.axes, dofs, struts, kEnvelope);
  const MechanismRangeProof proof = prove_stroke_ranges(m, kEnvelope);
  ASSERT_EQ(proof.reach, MechanismReach::kViolated);
  EXPECT_EQ(proof.witness_strut, 0u);
  EXPECT_LT(proof.witness_stroke, 0.010);
  MandibleStrokes s{};
  strokes(m, proof.witness, s);
  EXPECT_NEAR(s[0], proof.witness_stroke, 1e-12);
  EXPECT_NEAR(proof.witness.pitch_rad, 18 * kDeg, 1e-9);  // fully open
}

TEST(MechanismRangeProof, ConstraintsThatExcludeEverythingGiveAnEmptySet) {
  const MandibleMechanism m = proposed_mechanism(3);
  const std::array<MandibleLinearConstraint, 1> none = {
      MandibleLinearConstraint{{1.0, 0.0, 0.0}, -10 * kDeg}};  // pitch <= -10°
  const MechanismRangeProof proof = prove_stroke_ranges(m, kEnvelope, none);
  EXPECT_TRUE(proof.empty);
  EXPECT_EQ(proof.reach, MechanismReach::kProven);
}

// Random geometries, not just the well-behaved proposal: anchors anywhere in a
// head-sized box, envelopes up to ±30°. The bound holds regardless.
TEST(MechanismRangeProof, SoundForRandomGeometries) {
  const face::MandibleAxes& axes = testing::default_head_axes();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-0.12, 0.12), unit(0.0, 1.0);
  int proven = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::array<MandibleStrut, 3> struts{};
    for (MandibleStrut& s : struts) {
      s.skull = {coord(rng), coord(rng), coord(rng)};
      s.mandible = {coord(rng), coord(rng), coord(rng)};
      s.stroke_at_rest = 0.05;
      s.stroke = {0.0, 0.1};
    }
    const std::array<MandibleDof, 3> dofs = {MandibleDof::kPitch, MandibleDof::kYaw,
                                             MandibleDof::kProtrusion};
    const MandibleEnvelope env = {{-30 * kDeg * unit(rng), 30 * kDeg * unit(rng)},
                                  {-30 * kDeg * unit(rng), 30 * kDeg * unit(rng)},
                                  {-0.02 * unit(rng), 0.02 * unit(rng)}};
    MandibleMechanism m;
    try {
      m = make_mandible_mechanism(axes, dofs, struts, env, {}, {}, 1e12);
    } catch (const std::invalid_argument&) {
      continue;  // a strut of zero length
    }
    const MechanismRangeProof proof = prove_stroke_ranges(m, env);
    std::uniform_real_distribution<double> p(env.pitch.min, env.pitch.max),
        y(env.yaw.min, env.yaw.max), d(env.protrusion.min, env.protrusion.max);
    for (long n = 0; n < testing::sample_count(25'000); ++n) {
      MandibleStrokes s{};
      strokes(m, {p(rng), y(rng), d(rng)}, s);
      for (std::size_t i = 0; i < 3; ++i) {
        ASSERT_GE(s[i], proof.strut[i].proven.min) << trial << " " << i;
        ASSERT_LE(s[i], proof.strut[i].proven.max) << trial << " " << i;
      }
    }
    ++proven;
    for (std::size_t i = 0; i < 3; ++i) EXPECT_TRUE(proof.strut[i].converged) << trial;
  }
  EXPECT_GT(proven, 30);
}

}  // namespace
}  // namespace facectl
