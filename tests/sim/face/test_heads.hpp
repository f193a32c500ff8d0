// Synthetic test heads for `facectl face fit-head`: the default skin under a smooth
// non-uniform warp (other proportions), with a different vertex count and a shuffled
// vertex order, so a fit cannot lean on the default's indices. The vertex count changes
// either by longest-edge splitting (the default's vertices stay, moved by the warp) or by
// resampling the warped surface on a regular front-view grid (no vertex of the default
// stays: the skin landmarks' truth is not among the vertices). Because the warp is known,
// so is where every landmark truly lies on the new head.
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
  int vertices = 0;               // skin vertex count (after splitting or resampling)
  unsigned shuffle_seed = 1;
  // > 0: resampled on a front-view grid of this spacing (metres) instead of split.
  double grid = 0;

  // Metres in, metres out; smooth (tanh blend over 3 cm around y = −2 cm).
  Vec3 apply(const Vec3& p) const {
    const double below = 0.5 * (1 - std::tanh((p.y() + 0.02) / 0.03));
    const double r2 = (p.x() * p.x() + p.y() * p.y()) / (0.025 * 0.025);
    return {p.x() * sx * (1 + jaw * below), p.y() * sy, p.z() * sz + nose * std::exp(-r2)};
  }
};

// The shipped test heads (tests/data/heads/<name>/skin.obj).
inline std::vector<HeadWarp> test_head_warps() {
  return {
      // Longer face (+20 %), jaw 22 % wider, shallower; 1200 vertices, centimetres.
      {"long_wide_jaw", 1.0, 1.2, 0.9, 0.22, 0.0, 0.01, 1200, 7},
      // Broader (+18 %) and shorter (−15 %) face, deeper, the chin 15 % narrower and the
      // nose 6 mm longer; 800 vertices, millimetres.
      {"broad_short", 1.18, 0.85, 1.1, -0.15, 0.006, 0.001, 800, 11},
      // Narrower (−8 %) and longer (+6 %), the jaw 12 % wider and the nose 4 mm longer,
      // resampled on a 4 mm grid (1428 vertices); centimetres.
      {"grid_narrow", 0.92, 1.06, 1.0, 0.12, 0.004, 0.01, 1428, 5, 0.004},
  };
}

// A mesh renumbered: its vertices in a random order (old_of[k] is the input's index of
// vertex k) and, with `reorder_faces`, each face's corners rotated (the winding kept) and
// the faces in a random order.
struct Renumbered {
  TriMesh mesh;
  std::vector<int> old_of;
};
Renumbered renumbered(const TriMesh& m, unsigned seed, bool reorder_faces);

// The default skin with its openings cut, warped, refined to w.vertices (or resampled on
// the grid) and shuffled.
TriMesh make_test_head(const HeadSpec& source, const HeadWarp& w);

// Where source landmark `l` lies on the warped head (metres).
Vec3 true_landmark(const HeadSpec& source, const TriMesh& source_skin, const LandmarkSpec& l,
                   const HeadWarp& w);

}  // namespace facectl::face::testing
