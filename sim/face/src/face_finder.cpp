#include "facectl/face/face_finder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "facectl/face/head_fit.hpp"
#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// The frontmost used vertex, and the used vertices' extent in x and y. `used` is
// used_vertices(m) (the same for every turn of a mesh).
struct Front {
  Vec3 tip;
  double width = 0, height = 0;
};
Front front_of(const TriMesh& m, const std::vector<char>& used) {
  Front f;
  f.tip = Vec3::Constant(-std::numeric_limits<double>::infinity());
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < m.v.size(); ++i) {
    if (!used[i]) continue;
    const Vec3 p = m.v.get(i);
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    if (p.z() > f.tip.z()) f.tip = p;
  }
  f.width = hi.x() - lo.x(), f.height = hi.y() - lo.y();
  return f;
}

// Width (x extent) of the used vertices level with the tip (within 5% of the height).
double width_at_tip(const TriMesh& m, const std::vector<char>& used, const Front& f) {
  double lo = f.tip.x(), hi = f.tip.x();
  for (std::size_t i = 0; i < m.v.size(); ++i)
    if (used[i] && std::abs(m.v.y[i] - f.tip.y()) < 0.05 * f.height)
      lo = std::min(lo, m.v.x[i]), hi = std::max(hi, m.v.x[i]);
  return hi - lo;
}

// How far the tip stands out of the surface beside it, over the width: level with it and
// 15% of the width to either side, the surface is that much further back. A nose stands
// out (0.18 on the default head); the back of a skull is round (under 0.05).
double protrusion(const TriMesh& m, const std::vector<char>& used) {
  const Front f = front_of(m, used);
  double beside = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < m.v.size(); ++i)
    if (used[i] && std::abs(m.v.y[i] - f.tip.y()) < 0.05 * f.height &&
        std::abs(m.v.x[i] - f.tip.x()) > 0.15 * f.width)
      beside = std::max(beside, m.v.z[i]);
  return std::isfinite(beside) ? (f.tip.z() - beside) / f.width : 0;
}

// The turn (degrees) in [from, to] by `step` at which the turned head is most nearly
// mirror-symmetric, and that asymmetry.
std::pair<double, double> most_symmetric(const TriMesh& head, double from, double to, double step) {
  std::pair<double, double> best{from, std::numeric_limits<double>::infinity()};
  for (double a = from; a <= to + 1e-9; a += step) {
    const double asym = mirror_asymmetry(turned_about_y(head, a), 0);
    if (asym < best.second) best = {a, asym};
  }
  return best;
}

// Keeps the triangles whose vertices all lie in `keep`, then drops the vertices no kept
// triangle uses (renumbering the rest in order).
TriMesh cut(const TriMesh& m, const std::vector<char>& keep) {
  TriMesh out;
  std::vector<int> index(m.v.size(), -1);
  for (const Tri& t : m.tris) {
    if (!keep[t[0]] || !keep[t[1]] || !keep[t[2]]) continue;
    Tri u;
    for (int k = 0; k < 3; ++k) {
      int& j = index[static_cast<std::size_t>(t[k])];
      if (j < 0) {
        j = static_cast<int>(out.v.size());
        out.v.push_back(m.v.get(t[k]));
      }
      u[k] = j;
    }
    out.tris.push_back(u);
  }
  return out;
}

}  // namespace

TriMesh turned_about_y(TriMesh m, double degrees) {
  const double c = std::cos(degrees * kDegree), s = std::sin(degrees * kDegree);
  for (std::size_t i = 0; i < m.v.size(); ++i) {
    const Vec3 p = m.v.get(i);
    m.v.set(i, Vec3(c * p.x() + s * p.z(), p.y(), -s * p.x() + c * p.z()));
  }
  return m;
}

FoundFace find_face(const TriMesh& head, const TriMesh& source_face, const std::string& what) {
  FoundFace found;
  found.head_vertices = head.v.size();
  const std::vector<char> head_used = used_vertices(head);
  // The facing axis: the most symmetric turn, 5 degrees apart, refined to 2.5 degrees.
  // Facing +z and facing -z are both symmetric (the plane passes through the nose or the
  // back of the skull); facing along x, the plane through an ear is not. The symmetric
  // basin is narrow (turned 10 degrees, the default face measures 0.165, worse than a
  // head seen from the side), so the steps must be fine.
  const auto coarse = most_symmetric(head, 0, 355, 5);
  auto [turn, asym] = most_symmetric(head, coarse.first - 2.5, coarse.first + 2.5, 2.5);
  constexpr double kSymmetric = 0.07;  // check_face_region's bound
  if (!(asym <= kSymmetric))
    throw InputError(what + ": no face found: turned about y, the mesh is nowhere " +
                     "mirror-symmetric about an upright plane (at best a tenth of its " +
                     "mirrored points land over " +
                     std::to_string(static_cast<int>(std::lround(100 * asym))) +
                     "% of its width from the surface): expected a head with y up");
  // Front or back: the nose stands out, the back of the skull does not. The back is
  // measured at the opposite turn (front and back share the mirror plane).
  const double back = turn + 180;
  double stands_out = protrusion(turned_about_y(head, turn), head_used);
  if (const double b = protrusion(turned_about_y(head, back), head_used); b > stands_out)
    turn = back, stands_out = b, asym = mirror_asymmetry(turned_about_y(head, back), 0);
  constexpr double kNose = 0.08;  // the default face 0.18; a round skull under 0.05
  if (!(stands_out >= kNose))
    throw InputError(what + ": no face found: mirror-symmetric turned " +
                     std::to_string(static_cast<int>(std::lround(turn))) +
                     " degrees about y, but nothing stands out in front like a nose (" +
                     std::to_string(static_cast<int>(std::lround(100 * stands_out))) +
                     "% of the width, a nose 18%)");
  turn = std::remainder(turn, 360.0);
  const TriMesh turned = turned_about_y(head, turn);
  found.turn_degrees = turn;
  found.asymmetry = asym;
  found.protrusion = stands_out;
  // A face mask that was only turned is kept whole: the cut below is for whole heads, and
  // on a face longer than the source's in proportion it would cut off the chin.
  try {
    check_face_region(turned, what);
    found.mesh = turned;
    found.kept_vertices = turned.v.size();
    return found;
  } catch (const InputError&) {
  }

  // The source face's extent around its nose tip, scaled by the widths level with the tips.
  const std::vector<char> source_used = used_vertices(source_face);
  const Front sf = front_of(source_face, source_used), hf = front_of(turned, head_used);
  const double k = width_at_tip(turned, head_used, hf) / width_at_tip(source_face, source_used, sf);
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < source_face.v.size(); ++i)
    if (source_used[i]) {
      const Vec3 d = k * (source_face.v.get(i) - sf.tip);
      lo = lo.cwiseMin(d), hi = hi.cwiseMax(d);
    }
  std::vector<char> keep(turned.v.size(), 0);
  for (std::size_t i = 0; i < turned.v.size(); ++i) {
    const Vec3 d = turned.v.get(i) - hf.tip;
    keep[i] =
        d.y() >= lo.y() && d.y() <= hi.y() && d.z() >= lo.z() && d.x() >= lo.x() && d.x() <= hi.x();
  }
  found.mesh = cut(turned, keep);
  found.cut = true;
  found.kept_vertices = found.mesh.v.size();
  // What is left must still be a mesh the fit can take (enough vertices, manifold).
  check_mesh_basics(found.mesh, what + " (the face cut from it)");
  return found;
}

}  // namespace facectl::face
