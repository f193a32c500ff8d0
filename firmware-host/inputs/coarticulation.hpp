// Viseme weights over time from phoneme timings, with coarticulation by the
// dominance model of Cohen & Massaro (1993), "Modeling coarticulation in
// synthetic visual speech", in Thalmann & Thalmann (eds.), Models and
// Techniques in Computer Animation, Springer, pp. 139-156.
#pragma once

#include <array>
#include <vector>

#include "firmware-host/inputs/phoneme_track.hpp"

namespace facectl {

// How strongly, and how far beyond its own span, one class of segments pulls
// the mouth towards its viseme. The model's rates are per segment: each
// segment's dominance
//   D(t) = alpha * exp(-theta * |t - centre|^c)
// uses theta_before before its centre and theta_after after it, chosen so
// that D is alpha / 2 reach_before_s before the segment's start and
// reach_after_s after its end. A segment longer than 2 * max_half_s holds
// full dominance over its own span (|t - centre| is measured from the edge of
// that flat top) and reaches beyond its ends as one of 2 * max_half_s does,
// so that a long pause or vowel does not reach across phrases.
struct DominanceClass {
  double alpha = 1.0;
  double reach_before_s = 0.04;
  double reach_after_s = 0.04;
};

// Defaults are this project's choices, not values fitted by Cohen & Massaro
// (they fit per-speaker, per-feature parameters to measured lip tracks, which
// do not transfer to a robot face); their ordering follows the paper's
// argument: lip closures resist coarticulation, lingual consonants let the
// lips follow the vowels, and rounding is anticipated well ahead.
struct CoarticulationParams {
  // Anticipatory rounding: for the rounded visemes (6 ch_j_sh, 9 r, 13 o,
  // 14 U) dominance is half its peak lookahead_s before the segment starts.
  // Bell-Berti & Harris (1979, JASA 65) found rounding for /u/ starting a
  // roughly fixed time before the vowel, Daniloff & Moll (1968, JSHR 11) up to
  // four consonants ahead; 0.12 s, about two short consonants, is our choice.
  double lookahead_s = 0.12;
  // c: 2 gives a bell, flat at the centre, so long segments reach their target.
  double exponent = 2.0;
  double max_half_s = 0.15;
  DominanceClass vowel{1.0, 0.04, 0.06};      // 10 a, 11 e, 12 i
  DominanceClass rounded{1.0, 0.12, 0.06};    // reach_before_s is replaced by lookahead_s
  DominanceClass closure{1.5, 0.02, 0.02};    // 1 p_b_m, 2 f_v
  DominanceClass consonant{0.5, 0.02, 0.02};  // 3 th, 4 t_d, 5 k_g, 7 s_z, 8 n_l
  DominanceClass silence{0.1, 0.02, 0.02};    // 0: relaxes the mouth only in long pauses
  // Neutral pull present everywhere, so the mouth returns to rest (viseme 0)
  // before the first and after the last segment and in unlabelled gaps.
  double rest_dominance = 0.01;
  // Closures seal: over centre +- min(closure_hold_s, 40 % of the segment) the
  // output is exactly the closure viseme, eased in and out over the rest of
  // it, the easing at most 40 ms at each end (a long "mmm" stays sealed).
  double closure_hold_s = 0.02;
  // Dominance below this fraction of a segment's peak is dropped (and the
  // rest lowered by it, so weights stay continuous).
  double cutoff = 1e-4;
};

class VisemeTimeline {
 public:
  // Throws std::invalid_argument for parameters out of range.
  static VisemeTimeline build(const PhonemeTrack& track, const CoarticulationParams& params);

  double duration() const { return duration_; }
  // Weights of the 15 visemes at time t, summing to 1. No allocation; cost
  // grows with the segments within reach of t, found by binary search.
  void weights(double t, std::array<double, kVisemeCount>& out) const;

 private:
  struct Segment {
    double start, end, centre, flat, alpha, theta_before, theta_after, lo, hi, hold;
    int viseme;
    bool closure;
  };
  std::vector<Segment> segments_;
  double duration_ = 0.0;
  double exponent_ = 2.0;
  double rest_ = 0.01;
  double cutoff_ = 1e-4;
  double max_before_ = 0.0;  // max of start - lo: how far back a segment reaches
  double max_after_ = 0.0;   // max of hi - end
};

// The weights at t = 0, 1/rate_hz, ... up to and including duration().
std::vector<std::array<double, kVisemeCount>> sample_timeline(const VisemeTimeline& timeline,
                                                              double rate_hz);

}  // namespace facectl
