#include "firmware-host/inputs/coarticulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace facectl {
namespace {

constexpr double kMaxClosureRamp = 0.04;  // s

bool is_closure(int v) {
  return v == kVisemePBM || v == kVisemeFV;
}
bool is_rounded(int v) {
  return v == kVisemeChJSh || v == kVisemeR || v == kVisemeO || v == kVisemeU;
}

DominanceClass class_of(int v, const CoarticulationParams& p) {
  if (v == kVisemeNone) return p.silence;
  if (is_closure(v)) return p.closure;
  if (is_rounded(v)) return {p.rounded.alpha, p.lookahead_s, p.rounded.reach_after_s};
  if (v >= kVisemeA) return p.vowel;
  return p.consonant;
}

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("CoarticulationParams: ") + what);
}

void check(const DominanceClass& c, const char* name) {
  require(std::isfinite(c.alpha) && c.alpha > 0.0, name);
  require(std::isfinite(c.reach_before_s) && c.reach_before_s >= 0.0, name);
  require(std::isfinite(c.reach_after_s) && c.reach_after_s >= 0.0, name);
}

// 0 at u <= 0, 1 at u >= 1, flat at both ends.
double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

}  // namespace

VisemeTimeline VisemeTimeline::build(const PhonemeTrack& track, const CoarticulationParams& p) {
  require(std::isfinite(p.exponent) && p.exponent >= 0.5 && p.exponent <= 8.0, "exponent");
  require(std::isfinite(p.lookahead_s) && p.lookahead_s >= 0.0, "lookahead_s");
  require(std::isfinite(p.max_half_s) && p.max_half_s > 0.0, "max_half_s");
  require(std::isfinite(p.rest_dominance) && p.rest_dominance > 0.0, "rest_dominance");
  require(std::isfinite(p.closure_hold_s) && p.closure_hold_s >= 0.0, "closure_hold_s");
  require(p.cutoff > 0.0 && p.cutoff < 0.5, "cutoff");
  check(p.vowel, "vowel");
  check(p.rounded, "rounded");
  check(p.closure, "closure");
  check(p.consonant, "consonant");
  check(p.silence, "silence");

  VisemeTimeline tl;
  tl.exponent_ = p.exponent;
  tl.rest_ = p.rest_dominance;
  tl.cutoff_ = p.cutoff;
  tl.duration_ = track.duration_s;
  // Distance, in units of the half-dominance distance, at which D falls to cutoff.
  const double window = std::pow(std::log(1.0 / p.cutoff) / std::numbers::ln2, 1.0 / p.exponent);
  double prev_end = 0.0;
  for (const PhonemeSegment& s : track.segments) {
    require(s.viseme >= 0 && s.viseme < kVisemeCount, "segment viseme out of 0..14");
    require(std::isfinite(s.start_s) && std::isfinite(s.end_s) && s.end_s >= s.start_s &&
                s.start_s >= prev_end - kSegmentOverlapTolerance,
            "segments out of order");
    prev_end = s.end_s;
    const DominanceClass c = class_of(s.viseme, p);
    // A segment longer than 2 * max_half_s keeps its own span at full
    // dominance (a flat top) and reaches as far beyond its ends as one of
    // that length: a held "mmm" stays closed, a long vowel stays open.
    const double real_half = 0.5 * (s.end_s - s.start_s);
    const double half = std::min(real_half, p.max_half_s);
    // Half-dominance distances from the centre; kept above 1 ms for zero-length segments.
    const double before = std::max(half + c.reach_before_s, 1e-3);
    const double after = std::max(half + c.reach_after_s, 1e-3);
    Segment g{};
    g.start = s.start_s;
    g.end = s.end_s;
    g.centre = 0.5 * (s.start_s + s.end_s);
    g.flat = real_half - half;
    g.alpha = c.alpha;
    g.theta_before = std::numbers::ln2 / std::pow(before, p.exponent);
    g.theta_after = std::numbers::ln2 / std::pow(after, p.exponent);
    g.lo = g.centre - g.flat - window * before;
    g.hi = g.centre + g.flat + window * after;
    g.viseme = s.viseme;
    g.closure = is_closure(s.viseme);
    g.hold = std::min(p.closure_hold_s, 0.4 * (s.end_s - s.start_s));
    tl.max_before_ = std::max(tl.max_before_, g.start - g.lo);
    tl.max_after_ = std::max(tl.max_after_, g.hi - g.end);
    tl.segments_.push_back(g);
    tl.duration_ = std::max(tl.duration_, s.end_s);
  }
  return tl;
}

void VisemeTimeline::weights(double t, std::array<double, kVisemeCount>& out) const {
  out.fill(0.0);
  out[kVisemeNone] = rest_;
  double total = rest_;
  double seal = 0.0;  // how far a closure overrides the blend, 0..1
  int seal_viseme = 0;
  // Candidates start no later than t + max_before_ and end no earlier than
  // t - max_after_; ends grow with starts, so walk back from the first bound.
  const auto last = std::upper_bound(segments_.begin(), segments_.end(), t + max_before_,
                                     [](double x, const Segment& s) { return x < s.start; });
  for (auto it = last; it != segments_.begin();) {
    const Segment& s = *--it;
    if (s.end < t - max_after_) break;
    if (t < s.lo || t > s.hi) continue;
    if (s.closure && t >= s.start && t <= s.end) {
      // Eased in from the start and out to the end, over at most
      // kMaxClosureRamp: a held "mmm" is sealed for all but its edges.
      const double ramp = std::min(s.centre - s.hold - s.start, kMaxClosureRamp);
      double k = 1.0;
      if (t < s.start + ramp) k = ramp > 0 ? smoothstep((t - s.start) / ramp) : 1.0;
      if (t > s.end - ramp) k = ramp > 0 ? smoothstep((s.end - t) / ramp) : 1.0;
      seal = k;
      seal_viseme = s.viseme;
    }
    const double tau = std::max(0.0, std::abs(t - s.centre) - s.flat);
    const double theta = t < s.centre ? s.theta_before : s.theta_after;
    const double d = s.alpha * (std::exp(-theta * std::pow(tau, exponent_)) - cutoff_);
    if (d <= 0.0) continue;
    out[static_cast<std::size_t>(s.viseme)] += d;
    total += d;
  }
  for (double& w : out) w = (1.0 - seal) * w / total;
  out[static_cast<std::size_t>(seal_viseme)] += seal;
}

std::vector<std::array<double, kVisemeCount>> sample_timeline(const VisemeTimeline& timeline,
                                                              double rate_hz) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw std::invalid_argument("sample_timeline: rate_hz must be positive");
  }
  const auto n = static_cast<std::size_t>(std::floor(timeline.duration() * rate_hz + 1e-9)) + 1;
  std::vector<std::array<double, kVisemeCount>> frames(n);
  for (std::size_t i = 0; i < n; ++i) timeline.weights(static_cast<double>(i) / rate_hz, frames[i]);
  return frames;
}

}  // namespace facectl
