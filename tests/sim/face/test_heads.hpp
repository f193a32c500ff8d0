// Synthetic test heads for `facectl face fit-head`: the default skin under a smooth
// non-uniform warp (other proportions), with a different vertex count (longest-edge
// splitting) and a shuffled vertex order, so a fit cannot lean on the default's indices.
// Because the warp is known, so is where every landmark truly lies on the new head.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "facectl/face/head_spec.hpp"
#include "facectl/face/mesh.hpp"

namespace facectl::face::testing {

struct HeadWarp {
  std::string name;
  double sx = 1, sy = 1, sz = 1;  // overall scale per axis
  double jaw = 0;                 // extra width below the nose, fading out above it
  double nose = 0;                // metres of extra forward z at the nose, Gaussian (σ 2.5 cm)
  double units = 0.01;            // metres per OBJ unit when written
  int vertices = 0;               // skin vertex count after splitting
  unsigned shuffle_seed = 1;

  // Metres in, metres out; smooth (tanh blend over 3 cm around y = −2 cm).
  Vec3 apply(const Vec3& p) const {
    const double below = 0.5 * (1 - std::tanh((p.y() + 0.02) / 0.03));
    const double r2 = (p.x() * p.x() + p.y() * p.y()) / (0.025 * 0.025);
    return {p.x() * sx * (1 + jaw * below), p.y() * sy, p.z() * sz + nose * std::exp(-r2)};
  }
};

// The two shipped test heads (tests/data/heads/<name>/skin.obj).
inline std::vector<HeadWarp> test_head_warps() {
  return {
      // Longer face (+20 %), jaw 22 % wider, shallower; 1200 vertices, centimetres.
      {"long_wide_jaw", 1.0, 1.2, 0.9, 0.22, 0.0, 0.01, 1200, 7},
      // Broader (+18 %) and shorter (−15 %) face, deeper, the chin 15 % narrower and the
      // nose 6 mm longer; 800 vertices, millimetres.
      {"broad_short", 1.18, 0.85, 1.1, -0.15, 0.006, 0.001, 800, 11},
  };
}

// The default skin with its openings cut, warped, refined to w.vertices and shuffled.
TriMesh make_test_head(const HeadSpec& source, const HeadWarp& w);

// Where source landmark `l` lies on the warped head (metres).
Vec3 true_landmark(const HeadSpec& source, const TriMesh& source_skin, const LandmarkSpec& l,
                   const HeadWarp& w);

}  // namespace facectl::face::testing
