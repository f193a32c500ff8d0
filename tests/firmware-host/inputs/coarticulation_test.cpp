#include "firmware-host/inputs/coarticulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

namespace facectl {
namespace {

using Weights = std::array<double, kVisemeCount>;

// Back-to-back segments from `start`, written "AA1 0.1, M 0.05" (phone, seconds).
PhonemeTrack track(const std::string& phones, double start = 0.2) {
  PhonemeTrack t;
  double at = start;
  std::istringstream in(phones);
  std::string label, len;
  while (in >> label >> len) {
    if (len.back() == ',') len.pop_back();
    const double d = std::stod(len);
    t.segments.push_back({at, at + d, label, viseme_of_phone(label), 0});
    at += d;
  }
  t.duration_s = at;
  return t;
}

Weights weights_at(const VisemeTimeline& tl, double t) {
  Weights w{};
  tl.weights(t, w);
  return w;
}

TEST(CoarticulationTest, WeightsAreAPartitionOfOneEverywhere) {
  const VisemeTimeline tl = VisemeTimeline::build(
      track("HH 0.06, AH0 0.05, L 0.07, OW1 0.2, sil 0.4, M 0.08, IY1 0.12, F 0.1, "
            "UW1 0.3"),
      {});
  for (double t = -0.5; t < tl.duration() + 1.0; t += 0.001) {
    const Weights w = weights_at(tl, t);
    EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-12) << t;
    for (double x : w) {
      EXPECT_GE(x, 0.0) << t;
      EXPECT_LE(x, 1.0) << t;
    }
  }
}

TEST(CoarticulationTest, WeightsChangeContinuously) {
  // A short closure (M, 30 ms) eases in over 3 ms: the steepest slope here.
  const PhonemeTrack tr =
      track("S 0.05, P 0.06, AA1 0.1, M 0.03, AA1 0.1, B 0.08, sil 0.6, W 0.05, UW1 0.2");
  const VisemeTimeline tl = VisemeTimeline::build(tr, {});
  const double step = 1e-5;
  Weights prev = weights_at(tl, 0.0);
  double worst = 0.0, worst_t = 0.0;
  for (int i = 1; i * step < tl.duration() + 1.0; ++i) {
    const Weights w = weights_at(tl, i * step);
    for (int v = 0; v < kVisemeCount; ++v) {
      if (std::abs(w[v] - prev[v]) > worst) {
        worst = std::abs(w[v] - prev[v]);
        worst_t = i * step;
      }
    }
    prev = w;
  }
  EXPECT_LT(worst, 0.005) << "at " << worst_t << " s";
}

TEST(CoarticulationTest, BilabialClosesFullyEvenBetweenOpenVowels) {
  for (double len : {0.06, 0.02}) {
    const PhonemeTrack tr = track("AA1 0.15, M " + std::to_string(len) + ", AA1 0.15");
    const VisemeTimeline tl = VisemeTimeline::build(tr, {});
    const double centre = 0.5 * (tr.segments[1].start_s + tr.segments[1].end_s);
    const double hold = std::min(0.010, 0.4 * len);
    for (double dt = -hold; dt <= hold + 1e-12; dt += hold / 10) {
      const Weights w = weights_at(tl, centre + dt);
      for (int v = 0; v < kVisemeCount; ++v) {
        EXPECT_EQ(w[v], v == kVisemePBM ? 1.0 : 0.0) << len << " " << dt << " " << v;
      }
    }
    // Outside the hold the vowels show through.
    EXPECT_GT(weights_at(tl, tr.segments[1].start_s)[kVisemeA], 0.2);
  }
}

TEST(CoarticulationTest, LabiodentalClosesFullyToo) {
  const PhonemeTrack tr = track("IY1 0.12, V 0.05, IY1 0.12");
  const VisemeTimeline tl = VisemeTimeline::build(tr, {});
  EXPECT_EQ(weights_at(tl, 0.5 * (tr.segments[1].start_s + tr.segments[1].end_s))[kVisemeFV], 1.0);
}

TEST(CoarticulationTest, RoundingIsAnticipatedBeforeTheRoundedVowel) {
  const PhonemeTrack rounded = track("AA1 0.1, S 0.08, T 0.06, UW1 0.2");
  const PhonemeTrack spread = track("AA1 0.1, S 0.08, T 0.06, IY1 0.2");
  const VisemeTimeline a = VisemeTimeline::build(rounded, {});
  const VisemeTimeline b = VisemeTimeline::build(spread, {});
  const double vowel_start = rounded.segments[3].start_s;
  for (double before : {0.02, 0.06, 0.1, 0.14}) {
    const double t = vowel_start - before;
    const double u = weights_at(a, t)[kVisemeU];
    const double i = weights_at(b, t)[kVisemeI];
    EXPECT_GT(u, 0.2) << before;
    EXPECT_GT(u, i + 0.05) << before;
    EXPECT_GT(u, before >= 0.1 ? 1.5 * i : i) << before;  // far ahead, IY is barely felt
  }
  // In the middle of the consonants rounding already leads.
  EXPECT_GT(weights_at(a, vowel_start - 0.03)[kVisemeU], 0.4);
}

TEST(CoarticulationTest, LookaheadHalvesDominanceThatFarBeforeTheSegment) {
  // Alone against the rest pull, the weight is D / (D + rest): at lookahead_s
  // before the start D is half the peak.
  CoarticulationParams p;
  const PhonemeTrack tr = track("UW1 0.2", 1.0);
  const VisemeTimeline tl = VisemeTimeline::build(tr, p);
  const double d = p.rounded.alpha * (0.5 - p.cutoff);
  EXPECT_NEAR(weights_at(tl, 1.0 - p.lookahead_s)[kVisemeU], d / (d + p.rest_dominance), 1e-12);
  p.lookahead_s = 0.2;
  const VisemeTimeline longer = VisemeTimeline::build(tr, p);
  EXPECT_GT(weights_at(longer, 0.85)[kVisemeU], weights_at(tl, 0.85)[kVisemeU]);
}

TEST(CoarticulationTest, LongVowelReachesItsTargetAtItsCentre) {
  const VisemeTimeline tl = VisemeTimeline::build(track("T 0.06, AA1 0.5, K 0.06"), {});
  EXPECT_GT(weights_at(tl, 0.2 + 0.06 + 0.25)[kVisemeA], 0.98);
  const VisemeTimeline alone = VisemeTimeline::build(track("EH1 0.3"), {});
  EXPECT_GT(weights_at(alone, 0.35)[kVisemeE], 0.98);
}

TEST(CoarticulationTest, RelaxesMonotonicallyToNeutralOutsideSpeech) {
  const PhonemeTrack tr = track("HH 0.05, AY1 0.15, AA1 0.1", 0.5);
  const VisemeTimeline tl = VisemeTimeline::build(tr, {});
  const double end = tr.segments.back().end_s;
  double prev = weights_at(tl, end)[kVisemeNone];
  for (double t = end + 0.001; t < end + 2.0; t += 0.001) {
    const double w = weights_at(tl, t)[kVisemeNone];
    EXPECT_GE(w, prev) << t;
    prev = w;
  }
  EXPECT_EQ(prev, 1.0);
  prev = weights_at(tl, 0.5)[kVisemeNone];
  for (double t = 0.499; t > -1.0; t -= 0.001) {
    const double w = weights_at(tl, t)[kVisemeNone];
    EXPECT_GE(w, prev) << t;
    prev = w;
  }
  EXPECT_EQ(prev, 1.0);
}

TEST(CoarticulationTest, SilenceRelaxesTheMouthOnlyInLongPauses) {
  const PhonemeTrack shrt = track("AA1 0.15, sil 0.08, AA1 0.15");
  const PhonemeTrack lng = track("AA1 0.15, sil 0.8, AA1 0.15");
  const VisemeTimeline s = VisemeTimeline::build(shrt, {});
  const VisemeTimeline l = VisemeTimeline::build(lng, {});
  EXPECT_LT(weights_at(s, 0.2 + 0.15 + 0.04)[kVisemeNone], 0.2);
  EXPECT_GT(weights_at(l, 0.2 + 0.15 + 0.4)[kVisemeNone], 0.99);
}

TEST(CoarticulationTest, SamplesAtAFixedRateAndChecksParameters) {
  const VisemeTimeline tl = VisemeTimeline::build(track("AA1 0.3", 0.0), {});
  const auto frames = sample_timeline(tl, 100.0);
  ASSERT_EQ(frames.size(), 31u);
  EXPECT_EQ(frames[15], weights_at(tl, 0.15));
  EXPECT_THROW(sample_timeline(tl, 0.0), std::invalid_argument);
  CoarticulationParams bad;
  bad.closure.alpha = 0.0;
  EXPECT_THROW(VisemeTimeline::build({}, bad), std::invalid_argument);
  bad = {};
  bad.rest_dominance = -1;
  EXPECT_THROW(VisemeTimeline::build({}, bad), std::invalid_argument);
  PhonemeTrack wrong = track("AA1 0.3");
  wrong.segments[0].viseme = 15;
  EXPECT_THROW(VisemeTimeline::build(wrong, {}), std::invalid_argument);
  // An empty track rests.
  EXPECT_EQ(weights_at(VisemeTimeline::build({}, {}), 1.0)[kVisemeNone], 1.0);
}

TEST(CoarticulationTest, ALongClosureStaysClosedAndALongVowelStaysOpen) {
  // Longer than 2 * max_half_s (0.3 s): their own span keeps full dominance.
  const VisemeTimeline closure = VisemeTimeline::build(track("AA1 0.15, M 2.0, AA1 0.15"), {});
  for (double t = 0.2 + 0.15 + 0.045; t < 0.2 + 0.15 + 2.0 - 0.045; t += 0.01) {  // past the ramps
    EXPECT_DOUBLE_EQ(weights_at(closure, t)[kVisemePBM], 1.0) << t;
  }
  const VisemeTimeline vowel = VisemeTimeline::build(track("AA1 2.0"), {});
  for (double t = 0.2 + 0.05; t < 0.2 + 2.0 - 0.05; t += 0.01) {
    EXPECT_GT(weights_at(vowel, t)[kVisemeA], 0.95) << t;
  }
}

TEST(CoarticulationTest, TheLookAheadDoesNotShrinkForALongRoundedVowel) {
  // 120 ms before UW starts, rounding reaches as far as for a short UW.
  const double start = 0.2 + 0.3;
  const double shorter =
      weights_at(VisemeTimeline::build(track("AA1 0.3, UW1 0.2"), {}), start - 0.12)[kVisemeU];
  const double longer =
      weights_at(VisemeTimeline::build(track("AA1 0.3, UW1 1.0"), {}), start - 0.12)[kVisemeU];
  EXPECT_GT(shorter, 0.05);
  EXPECT_NEAR(longer, shorter, 1e-9);
}

}  // namespace
}  // namespace facectl
