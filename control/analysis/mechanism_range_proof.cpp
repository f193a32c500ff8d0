#include "control/analysis/mechanism_range_proof.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace facectl {
namespace {

using Eigen::Vector3d;

// Absolute allowance for floating-point rounding in a box's value and radius, m.
// The computed strut length is off by a few ulps of 0.1 m (1e-17 m each); this is
// ten million times that, and a thousandth of the default tolerance.
constexpr double kRounding = 1e-9;

struct Box {
  Vector3d lo, hi;
  double bound = 0.0;             // σ·L(centre) + radius: no pose in the box exceeds it
  std::array<double, 3> share{};  // each DOF's part of the radius: where to split
};

bool operator<(const Box& a, const Box& b) {
  return a.bound < b.bound;
}

class StrutSearch {
 public:
  StrutSearch(const MandibleMechanism& m, std::size_t strut,
              std::span<const MandibleLinearConstraint> constraints)
      : m_(m), index_(strut), strut_(m.strut[strut]), constraints_(constraints) {
    const face::MandibleAxes& a = m.axes;
    const Vector3d r = strut_.mandible - a.pitch_point;
    pitch_radius_ = (r - a.pitch_axis * a.pitch_axis.dot(r)).norm();
  }

  // Strut length at q.
  double length(const Vector3d& q) const {
    return (mandible_anchor(m_, index_, q) - strut_.skull).norm();
  }

  bool admissible(const Vector3d& q) const {
    for (const MandibleLinearConstraint& c : constraints_)
      if (c.a.dot(q) > c.b) return false;
    return true;
  }

  // True if some constraint excludes the whole box (with a rounding allowance,
  // so that no admissible pose is ever pruned).
  bool excluded(const Box& box) const {
    const Vector3d c = 0.5 * (box.lo + box.hi), h = 0.5 * (box.hi - box.lo);
    for (const MandibleLinearConstraint& k : constraints_) {
      const double smallest = k.a.dot(c) - k.a.cwiseAbs().dot(h);
      const double slack = 1e-12 * (1.0 + std::fabs(k.b) + k.a.cwiseAbs().dot(c.cwiseAbs() + h));
      if (smallest > k.b + slack) return true;
    }
    return false;
  }

  // Bounds σ·L over the box with the tighter of two rigorous bounds; returns
  // σ·L(centre). With p the mandible anchor, Δ = q − c and half-widths h:
  //
  // Lipschitz:  |L(q) − L(c)| <= |p(q) − p(c)| <= r_p·hθ + (r_y + r_p·hθ)·hψ + hd,
  //   a chord being at most its radius times its angle (r_p: the anchor's
  //   distance from the pitch axis; r_y: the pitched anchor's distance from the
  //   yaw axis at the centre; pitch over the box moves it by r_p·hθ at most).
  // Second order:  p(q) = p(c) + Dp(c)·Δ + R with
  //   |R| <= ½·(r_p·hθ² + 2·r_p·hθ·hψ + (r_y + r_p·hθ)·hψ²),
  //   since |∂θθp| = r_p, |∂θψp| <= r_p, |∂ψψp| <= r_y over the box, and the
  //   protrusion terms vanish. Then
  //   L(q) <= max over the box's corners of |p(c) + Dp(c)·Δ − s| + |R|
  //   (a convex function of Δ peaks at a corner), and
  //   L(q) >= L(c) − Σ_k |∂_k L(c)|·h_k − |R|  (projecting on the unit e = (p(c) − s)/L(c)).
  // Far from a stationary point the first is as good; near one the second
  // closes the gap quadratically in the box size.
  double bound(Box& box, double sigma) const {
    const face::MandibleAxes& a = m_.axes;
    const Vector3d c = 0.5 * (box.lo + box.hi), h = 0.5 * (box.hi - box.lo);
    const Eigen::Matrix3d Y = face::rodrigues(a.yaw_axis, c[1]);
    const Vector3d r = face::rodrigues(a.pitch_axis, c[0]) * (strut_.mandible - a.pitch_point);
    const Vector3d w = r + a.pitch_point - a.yaw_point;
    const Vector3d yw = Y * w;
    const Vector3d d = yw + a.yaw_point + c[2] * a.protrusion_dir - strut_.skull;
    const double length = d.norm();
    const double yaw_radius = (w - a.yaw_axis * a.yaw_axis.dot(w)).norm() + pitch_radius_ * h[0];
    box.share = {pitch_radius_ * h[0], yaw_radius * h[1], h[2]};
    const double lipschitz = box.share[0] + box.share[1] + box.share[2];
    const double remainder =
        0.5 * (pitch_radius_ * h[0] * (h[0] + 2.0 * h[1]) + yaw_radius * h[1] * h[1]);
    Eigen::Matrix3d D;  // Dp(c), columns pitch, yaw, protrusion
    D.col(0) = Y * a.pitch_axis.cross(r);
    D.col(1) = a.yaw_axis.cross(yw);
    D.col(2) = a.protrusion_dir;
    double reach = 0.0;  // how far σ·L may exceed σ·L(c) over the box
    if (sigma > 0.0) {
      double corner = 0.0;
      for (int v = 0; v < 8; ++v) {
        const Vector3d delta((v & 1 ? h[0] : -h[0]), (v & 2 ? h[1] : -h[1]),
                             (v & 4 ? h[2] : -h[2]));
        corner = std::max(corner, (d + D * delta).norm());
      }
      reach = std::min(lipschitz, corner - length + remainder);
    } else {
      const Vector3d slope = D.transpose() * (d / length);  // ∂L/∂q at c
      reach = std::min(lipschitz, slope.cwiseAbs().dot(h) + remainder);
    }
    const double value = sigma * length;
    box.bound = value + std::max(reach, 0.0) * (1.0 + 1e-12) + kRounding;
    return value;
  }

  struct Result {
    double proven = 0.0, attained = 0.0;
    Vector3d witness = Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    bool found = false;      // an admissible pose was seen
    bool empty = false;      // every box was excluded
    bool converged = false;  // proven − attained <= tolerance
    std::size_t boxes = 0;
  };

  // The largest σ·L over the admissible poses of `root`.
  Result maximise(const Box& root_box, double sigma, const RangeProofOptions& options) const {
    Result r;
    r.attained = -std::numeric_limits<double>::infinity();
    double dropped = -std::numeric_limits<double>::infinity();  // largest bound let go
    auto consider = [&](const Vector3d& q, double value) {
      if (value > r.attained && admissible(q)) {
        r.attained = value;
        r.witness = q;
        r.found = true;
      }
    };
    // The envelope's corners first: for a near-linear stroke they are the answer.
    for (int corner = 0; corner < 8; ++corner) {
      Vector3d q;
      for (int k = 0; k < 3; ++k) q[k] = (corner >> k) & 1 ? root_box.hi[k] : root_box.lo[k];
      consider(q, sigma * length(q));
    }
    std::vector<Box> heap;
    heap.reserve(1 << 12);
    Box root = root_box;
    if (!excluded(root)) {
      consider(0.5 * (root.lo + root.hi), bound(root, sigma));
      heap.push_back(root);
      ++r.boxes;
    }
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end());
      const Box top = heap.back();
      heap.pop_back();
      if (r.found && top.bound - r.attained <= options.tolerance) {
        r.proven = std::max(top.bound, dropped);
        r.converged = true;
        return r;
      }
      if (r.boxes >= options.max_boxes) {
        r.proven = std::max(top.bound, dropped);
        return r;
      }
      const auto k = static_cast<Eigen::Index>(
          std::max_element(top.share.begin(), top.share.end()) - top.share.begin());
      const double mid = 0.5 * (top.lo[k] + top.hi[k]);
      for (int side = 0; side < 2; ++side) {
        Box child = top;
        (side == 0 ? child.hi : child.lo)[k] = mid;
        if (excluded(child)) continue;
        consider(0.5 * (child.lo + child.hi), bound(child, sigma));
        ++r.boxes;
        if (r.found && child.bound <= r.attained + options.tolerance) {
          dropped = std::max(dropped, child.bound);
          continue;
        }
        heap.push_back(child);
        std::push_heap(heap.begin(), heap.end());
      }
    }
    // Every box was either closed within tolerance or excluded.
    r.empty = !r.found && dropped == -std::numeric_limits<double>::infinity();
    r.proven = std::max(dropped, r.attained);
    r.converged = r.found;
    return r;
  }

 private:
  const MandibleMechanism& m_;
  std::size_t index_;
  const MandibleStrut& strut_;
  std::span<const MandibleLinearConstraint> constraints_;
  double pitch_radius_ = 0.0;
};

}  // namespace

MechanismRangeProof prove_stroke_ranges(const MandibleMechanism& m,
                                        const MandibleEnvelope& envelope,
                                        std::span<const MandibleLinearConstraint> constraints,
                                        const RangeProofOptions& options) {
  const std::array<Range, 3> range = {envelope.pitch, envelope.yaw, envelope.protrusion};
  for (const Range& r : range)
    if (!(r.min <= r.max) || !std::isfinite(r.min) || !std::isfinite(r.max))
      throw std::invalid_argument("mandible range proof: the envelope needs finite ranges");
  const Vector3d held = to_vector(m.held);
  Box root;
  for (std::size_t k = 0; k < 3; ++k) {
    root.lo[static_cast<Eigen::Index>(k)] = m.driven[k] ? range[k].min : held[k];
    root.hi[static_cast<Eigen::Index>(k)] = m.driven[k] ? range[k].max : held[k];
  }

  MechanismRangeProof proof;
  proof.count = m.count;
  bool undecided = false;
  bool violated = false;
  for (std::size_t i = 0; i < m.count; ++i) {
    const StrutSearch search(m, i, constraints);
    const auto high = search.maximise(root, 1.0, options);
    const auto low = search.maximise(root, -1.0, options);
    proof.boxes += high.boxes + low.boxes;
    if (high.empty || low.empty) {
      proof.empty = true;
      continue;
    }
    const MandibleStrut& s = m.strut[i];
    const double offset = s.stroke_at_rest - m.rest_length[i];
    StrokeEnclosure& e = proof.strut[i];
    e.proven = {offset - low.proven, offset + high.proven};
    e.attained = {offset - low.attained, offset + high.attained};
    e.argmin = to_pose(low.witness);
    e.argmax = to_pose(high.witness);
    e.converged = high.converged && low.converged;
    if (e.proven.min >= s.stroke.min && e.proven.max <= s.stroke.max) continue;
    if (!violated && (e.attained.max > s.stroke.max || e.attained.min < s.stroke.min)) {
      violated = true;
      const bool over = e.attained.max > s.stroke.max;
      proof.witness_strut = i;
      proof.witness = over ? e.argmax : e.argmin;
      proof.witness_stroke = over ? e.attained.max : e.attained.min;
      continue;
    }
    undecided = true;
  }
  if (proof.empty) {
    proof.reach = MechanismReach::kProven;  // nothing admissible, nothing to reach
    for (StrokeEnclosure& e : proof.strut) e = StrokeEnclosure{};
  } else {
    proof.reach = violated    ? MechanismReach::kViolated
                  : undecided ? MechanismReach::kUndecided
                              : MechanismReach::kProven;
  }
  return proof;
}

}  // namespace facectl
