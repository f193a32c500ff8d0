// The jaw pitch that open_jaw asks for, computed from the head's landmarks
// independently of the FAP mapping's closed form (docs/FAP.md, "Jaw").
#pragma once

#include "control/face/mandible.hpp"
#include "firmware-host/fap/fapu.hpp"

namespace facectl::testing {

// MNS0 as docs/FAP.md defines it: nose base (mid 9.1, 9.2) y − upper inner lip (2.2) y.
inline double mns0(const FeaturePoints& fp) {
  return 0.5 * (fp.at("fdp_9_1").y() + fp.at("fdp_9_2").y()) - fp.at("fdp_2_2").y();
}

// The pitch that lowers the chin (fdp_2_1) by `drop` metres, found by
// bisection on the rotation about the condyle line 2.14 -> 2.13.
inline double expected_jaw_pitch(const FeaturePoints& fp, double drop) {
  const face::Vec3 a = (fp.at("fdp_2_13") - fp.at("fdp_2_14")).normalized();
  const face::Vec3 p = fp.at("fdp_2_13");
  const face::Vec3 chin = fp.at("fdp_2_1");
  auto drop_at = [&](double t) {
    const face::Vec3 moved = face::rodrigues(a, t) * (chin - p) + p;
    return chin.y() - moved.y();
  };
  // The drop grows until the condyle-chin line is vertical (about 33 deg on
  // this head), so the bisection stays below that.
  double lo = -0.5, hi = 0.55;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (drop_at(mid) < drop ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace facectl::testing
