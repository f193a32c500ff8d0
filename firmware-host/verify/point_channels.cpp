#include "firmware-host/verify/point_channels.hpp"

#include <algorithm>

#include "control/analysis/channel_bound.hpp"

namespace facectl::verify {
namespace {

// The reduced model's polynomial over (muscles, jaw, eyelids) is bounded by
// branch and bound; signals outside the polynomial (eyes, neck) add their own
// box range, and coupled limits that involve them are left out (which only
// widens the set).
PointChannel bound_point_channel(const ControllerModel& m, const Polytope& set,
                                 std::size_t actuator) {
  // The polynomial's variables (muscles, jaw, eyelids) and the face signal of each.
  const std::size_t vars =
      static_cast<std::size_t>(face::constant_variable(m.layout.muscle_count()));
  std::vector<std::size_t> signal_of(vars);
  std::vector<int> var_of(set.size(), -1);
  const std::size_t n = m.layout.muscle_count();
  const std::size_t rigid[] = {m.layout.jaw_pitch(), m.layout.jaw_yaw(), m.layout.jaw_protrusion(),
                               m.layout.eyelid_closure(0), m.layout.eyelid_closure(1)};
  for (std::size_t v = 0; v < vars; ++v) {
    signal_of[v] = v < n ? v : rigid[v - n];  // the model's variable order after the muscles
    var_of[signal_of[v]] = static_cast<int>(v);
  }
  ChannelTerms terms;
  terms.offset = m.mapping.linear.offset(actuator);
  for (const PointTerm& p : m.mapping.points) {
    if (p.actuator != actuator) continue;
    terms.points.push_back({static_cast<int>(p.point), p.axis, p.gain});
  }
  PointChannel out;
  out.actuator = actuator;
  double outside_lo = 0.0, outside_hi = 0.0;
  out.at_lo.resize(set.size());
  out.at_hi.resize(set.size());
  for (std::size_t j = 0; j < set.size(); ++j) {
    const double g = m.mapping.linear.gain(actuator, j);
    out.at_lo[j] = out.at_hi[j] = std::clamp(m.neutral[j], set.lo[j], set.hi[j]);
    if (g == 0.0) continue;
    if (var_of[j] >= 0) {
      terms.linear.push_back({var_of[j], g});
    } else {
      out.at_lo[j] = g > 0 ? set.lo[j] : set.hi[j];
      out.at_hi[j] = g > 0 ? set.hi[j] : set.lo[j];
      outside_lo += g * out.at_lo[j];
      outside_hi += g * out.at_hi[j];
    }
  }
  const ChannelPolynomial poly = make_channel_polynomial(*m.mapping.reduced, terms);
  std::vector<Interval> box;
  for (std::size_t v = 0; v < vars; ++v)
    box.push_back({set.lo[signal_of[v]], set.hi[signal_of[v]]});
  std::vector<LinearInequality> rows;
  for (std::size_t r = 0; r < set.rows.size(); ++r) {
    bool inside = true;
    std::vector<double> a(vars, 0.0);
    for (std::size_t j = 0; j < set.size(); ++j) {
      if (set.rows[r][j] == 0.0) continue;
      if (var_of[j] < 0)
        inside = false;
      else
        a[static_cast<std::size_t>(var_of[j])] = set.rows[r][j];
    }
    if (inside) rows.push_back({std::move(a), set.rhs[r]});
  }
  const ChannelBound b = bound_channel(poly, box, rows);
  out.empty = b.empty;
  out.converged = b.converged;
  // The search leaves the variables it did not need (neither in the polynomial nor in a
  // limit) at their box's middle; the witnesses keep those at neutral, so that a finding
  // names only what drives the channel (as the LP witnesses do).
  std::vector<char> searched(vars, 0);
  for (int v : poly.used_variables()) searched[static_cast<std::size_t>(v)] = 1;
  for (const LinearInequality& row : rows)
    for (std::size_t v = 0; v < vars; ++v) searched[v] = searched[v] || row.a[v] != 0.0;
  for (std::size_t v = 0; v < vars; ++v) {
    if (!searched[v]) continue;
    if (v < b.witness_min.size()) out.at_lo[signal_of[v]] = b.witness_min[v];
    if (v < b.witness_max.size()) out.at_hi[signal_of[v]] = b.witness_max[v];
  }
  out.lo = b.lower + outside_lo;
  out.hi = b.upper + outside_hi;
  return out;
}

}  // namespace

std::vector<PointChannel> point_channels(const ControllerModel& m, const Polytope& set,
                                         const std::vector<std::size_t>& actuators) {
  std::vector<PointChannel> out;
  for (std::size_t a : actuators) out.push_back(bound_point_channel(m, set, a));
  return out;
}

}  // namespace facectl::verify
