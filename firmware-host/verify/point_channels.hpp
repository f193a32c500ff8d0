#pragma once

#include <vector>

#include "control/analysis/lp_range.hpp"
#include "control/controller_model.hpp"
#include "firmware-host/verify/proven_channel.hpp"

namespace facectl::verify {

// A channel that reads reduced-model control points, bounded by branch and
// bound; signals outside the polynomial sit in the witnesses where they push
// the bound.
struct PointChannel : ProvenChannel {
  bool empty = false;  // the admissible set, restricted to the polynomial, is empty
};

// One entry per actuator in `actuators`, in that order, each bounded with the default
// BoundOptions.
std::vector<PointChannel> point_channels(const ControllerModel& m, const Polytope& set,
                                         const std::vector<std::size_t>& actuators);

}  // namespace facectl::verify
