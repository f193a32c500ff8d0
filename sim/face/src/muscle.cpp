#include "facectl/face/muscle.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace facectl::face {
namespace {

int bot(const Muscle& m, int r, int c) {
  return m.first + r * m.cols + (c % m.cols);
}
int top(const Muscle& m, int r, int c) {
  return m.first + m.rows * m.cols + r * m.cols + (c % m.cols);
}

// Adds quad (a,b,c,d), wound a→b→c→d, as two triangles of the same winding, split along
// its shorter diagonal: a rule the mirror keeps, where one fixed diagonal gave a ring's
// two halves (its columns run the other way round in the mirror) different surfaces.
void add_quad(std::vector<Tri>& out, const Points& p, int a, int b, int c, int d) {
  if ((p.get(a) - p.get(c)).squaredNorm() <= (p.get(b) - p.get(d)).squaredNorm()) {
    out.push_back({a, b, c});
    out.push_back({a, c, d});
  } else {
    out.push_back({a, b, d});
    out.push_back({b, c, d});
  }
}

}  // namespace

void build_muscle_constraints(Muscle& m, const Points& p, const MuscleStiffness& k) {
  const bool ring = m.kind == MuscleKind::kSphincter;
  const int R = m.rows, C = m.cols, ccells = ring ? C : C - 1;
  // The box's faces are wound by the grid's own directions (column u, row v, bottom to
  // top w) so that every face turns the same way, outward or all inward, then turned
  // outward together by the sign of the enclosed volume. Deciding each triangle by its
  // cell's centre got thin boxes wrong (a 2 mm sheet over cells a centimetre wide): the
  // centre lies a millimetre from the top, and a top triangle tilted more than about 23°
  // against the cell turned the wrong way, so the rest volumes came out with either sign
  // and the volume constraint held an arbitrary function of the particles.
  m.surface.clear();
  for (int r = 0; r + 1 < R; ++r)
    for (int c = 0; c < ccells; ++c) {
      add_quad(m.surface, p, bot(m, r, c), bot(m, r + 1, c), bot(m, r + 1, c + 1),
               bot(m, r, c + 1));
      add_quad(m.surface, p, top(m, r, c), top(m, r, c + 1), top(m, r + 1, c + 1),
               top(m, r + 1, c));
      if (r == 0)
        add_quad(m.surface, p, bot(m, 0, c), bot(m, 0, c + 1), top(m, 0, c + 1), top(m, 0, c));
      if (r == R - 2)
        add_quad(m.surface, p, bot(m, R - 1, c), top(m, R - 1, c), top(m, R - 1, c + 1),
                 bot(m, R - 1, c + 1));
      if (!ring && c == 0)
        add_quad(m.surface, p, bot(m, r, 0), top(m, r, 0), top(m, r + 1, 0), bot(m, r + 1, 0));
      if (!ring && c == C - 2)
        add_quad(m.surface, p, bot(m, r, C - 1), bot(m, r + 1, C - 1), top(m, r + 1, C - 1),
                 top(m, r, C - 1));
    }
  VolumeConstraint enclosed;
  enclosed.tris = m.surface;
  if (volume_of(enclosed, p) < 0)
    for (Tri& t : m.surface) std::swap(t[1], t[2]);
  auto dist = [&](int a, int b, double kk) {
    if (kk > 0) m.distances.add(a, b, (p.get(a) - p.get(b)).norm(), kk);
  };
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < ccells; ++c) {  // latitudinal: along a row, between columns
      dist(top(m, r, c), top(m, r, c + 1), k.up_latitudinal);
      dist(bot(m, r, c), bot(m, r, c + 1), k.low_latitudinal);
    }
  for (int r = 0; r + 1 < R; ++r)
    for (int c = 0; c < C; ++c) {  // longitudinal: along a fibre, between rows
      dist(top(m, r, c), top(m, r + 1, c), k.up_longitudinal);
      dist(bot(m, r, c), bot(m, r + 1, c), k.low_longitudinal);
    }
  for (int r = 0; r < R; ++r)
    for (int c = 0; c < C; ++c)  // connections exist only on the box surface
      if (ring || r == 0 || r == R - 1 || c == 0 || c == C - 1)
        dist(bot(m, r, c), top(m, r, c), k.connection);
  for (int r = 0; r + 1 < R; ++r)
    for (int c = 0; c < ccells; ++c) {  // shear: both diagonals of top and bottom quads
      dist(top(m, r, c), top(m, r + 1, c + 1), k.up_shear);
      dist(top(m, r, c + 1), top(m, r + 1, c), k.up_shear);
      dist(bot(m, r, c), bot(m, r + 1, c + 1), k.low_shear);
      dist(bot(m, r, c + 1), bot(m, r + 1, c), k.low_shear);
    }
  // Shear diagonals on the side walls too (the box surface), at the mean shear stiffness;
  // without them the top can slide over the bottom as a parallelogram.
  const double wall = 0.5 * (k.up_shear + k.low_shear);
  for (int r : {0, R - 1})
    for (int c = 0; c < ccells; ++c) {
      dist(bot(m, r, c), top(m, r, c + 1), wall);
      dist(bot(m, r, c + 1), top(m, r, c), wall);
    }
  if (!ring)
    for (int c : {0, C - 1})
      for (int r = 0; r + 1 < R; ++r) {
        dist(bot(m, r, c), top(m, r + 1, c), wall);
        dist(bot(m, r + 1, c), top(m, r, c), wall);
      }
  order_in_runs(m.distances, p);
  if (k.bend > 0) add_bending(m.bending, p, m.surface, k.bend);
  m.volume = make_volume(p, m.surface, Vec3::Zero(), k.volume);
  for (int i = 0; i < R * C; ++i) m.attach.add(m.first + i, k.position);
}

double sheet_length_scale(double c) {
  if (c <= kSheetKnee) return 1 - c;
  // 1 − c + a·(c − knee)², a chosen so that it ends at kSheetShortest; its slope 2a·(1 −
  // knee) − 1 at c = 1 is then 0 (a·(1 − knee)² = kSheetShortest = (1 − knee)/2).
  const double t = c - kSheetKnee, span = 1 - kSheetKnee;
  return 1 - c + kSheetShortest / (span * span) * t * t;
}

void sample_polyline(const Points& poly, std::vector<double>& arc, bool closed, int n, double scale,
                     Points& out, int off) {
  const int np = static_cast<int>(poly.size());
  if (closed) {
    // Rings are sampled at fixed positions along their polyline (material sampling):
    // arc-length resampling of a ring stretched unevenly (the lower lip moving with the
    // jaw) slides every sample around the ring and breaks the face's symmetry.
    for (int i = 0; i < n; ++i) {
      const double u = static_cast<double>(i) * np / n;
      const int a = static_cast<int>(u);
      const double f = u - a;
      out.set(off + i, (1 - f) * poly.get(a % np) + f * poly.get((a + 1) % np));
    }
    return;
  }
  const int segs = np - 1;
  arc[0] = 0;
  for (int s = 0; s < segs; ++s)
    arc[s + 1] = arc[s] + (poly.get((s + 1) % np) - poly.get(s)).norm();
  const double total = arc[segs];
  const double step = total / (n - 1);  // erratum 4: L/(N−1)
  int seg = 0;
  for (int i = 0; i < n; ++i) {
    const double s = std::min(i * step * scale, total);
    while (seg < segs - 1 && arc[seg + 1] < s) ++seg;
    const double len = arc[seg + 1] - arc[seg];
    const double f = len > 0 ? (s - arc[seg]) / len : 0;
    out.set(off + i, (1 - f) * poly.get(seg) + f * poly.get(seg + 1));
  }
}

void muscle_targets(const Muscle& m, double c, const Points& skull, const Points& muscles,
                    MuscleScratch& s) {
  auto eval_line = [&](const std::vector<SurfacePoint>& line) {
    for (std::size_t i = 0; i < line.size(); ++i) {
      const SurfacePoint& sp = line[i];
      s.line_pos.set(i, sp.position(sp.layer == Layer::kSkull ? skull : muscles));
    }
  };
  if (m.kind == MuscleKind::kSheet) {
    for (int col = 0; col < m.cols; ++col) {
      s.line_pos.resize(m.lines[col].size());
      eval_line(m.lines[col]);
      sample_polyline(s.line_pos, s.arc, false, m.rows, sheet_length_scale(c), s.column, 0);
      for (int r = 0; r < m.rows; ++r) s.targets.set(r * m.cols + col, s.column.get(r));
    }
    return;
  }
  // Sphincter: resample both rings, then contract (§4.3.2).
  const int w = m.cols;
  for (int ring = 0; ring < 2; ++ring) {
    s.line_pos.resize(m.lines[ring].size());
    eval_line(m.lines[ring]);
    sample_polyline(s.line_pos, s.arc, true, w, 1.0, s.targets, ring * w);
  }
  if (c <= 0) return;
  // Least-squares contraction plane through all samples.
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < 2 * w; ++i) mean += s.targets.get(i);
  mean /= 2 * w;
  Mat3 cov = Mat3::Zero();
  for (int i = 0; i < 2 * w; ++i) {
    Vec3 d = s.targets.get(i) - mean;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Mat3> es(cov);
  const Vec3 nrm = es.eigenvectors().col(0);
  auto onto_plane = [&](const Vec3& q) { return Vec3(q - nrm.dot(q - mean) * nrm); };
  Vec3 guess = Vec3::Zero();
  for (int i = 0; i < w; ++i) guess += onto_plane(s.targets.get(i));
  guess /= w;  // erratum 10: the mean divides by w
  Vec3 o = Vec3::Zero();
  for (int i = 0; i < w; ++i) {  // closest points to the guess on the lines s1_i–s3_i
    Vec3 a = s.targets.get(i), d = s.targets.get(w + i) - a;
    double dd = d.squaredNorm();
    o += dd > 0 ? Vec3(a + d * (d.dot(guess - a) / dd)) : a;
  }
  o /= w;
  Vec3 da = onto_plane(o + Vec3::UnitX()) - o, db = onto_plane(o + Vec3::UnitY()) - o;
  da.normalize();
  db.normalize();
  double A = 1e-12, B = 1e-12;
  for (int i = 0; i < 2 * w; ++i) {
    A = std::max(A, (s.targets.get(i) - o).dot(da));
    B = std::max(B, (s.targets.get(i) - o).dot(db));
  }
  for (int i = 0; i < w; ++i) {
    Vec3 s1 = s.targets.get(i), s3 = s.targets.get(w + i);
    const double x = (s3 - o).dot(da), y = (s3 - o).dot(db);
    const double rho = std::sqrt(x * x * B * B + y * y * A * A) / (A * B);  // erratum 9
    const Vec3 delta = (o - s1) * c * std::cos(std::numbers::pi / 2 * (1 - std::min(rho, 1.0)));
    s.targets.set(i, s1 + delta);
    s.targets.set(w + i, s3 + delta);
  }
}

}  // namespace facectl::face

namespace facectl::face {

MuscleScratch make_muscle_scratch(std::size_t max_line, std::size_t max_grid) {
  MuscleScratch s;
  s.line_pos.resize(max_line);
  s.arc.resize(max_line + 1);
  s.column.resize(max_grid);
  s.targets.resize(2 * max_grid);
  return s;
}

void place_muscle(Muscle& m, double thickness, const std::function<Vec3(const Vec3&)>& normal_at,
                  const Points& skull, Points& pos, const MuscleStiffness& k) {
  std::size_t max_line = 0;
  for (const auto& l : m.lines) max_line = std::max(max_line, l.size());
  const int nb = m.rows * m.cols;
  MuscleScratch s = make_muscle_scratch(max_line, static_cast<std::size_t>(nb));
  m.first = static_cast<int>(pos.size());
  muscle_targets(m, 0.0, skull, pos, s);
  for (int i = 0; i < nb; ++i) pos.push_back(s.targets.get(i));
  for (int i = 0; i < nb; ++i) {
    const Vec3 p = s.targets.get(i);
    pos.push_back(p + thickness * normal_at(p));
  }
  build_muscle_constraints(m, pos, k);
}

void step_muscle(const Muscle& m, double c, const Points& skull, Points& pos,
                 const std::vector<double>& w, MuscleScratch& s, Points& grad) {
  // The goals depend only on the layers beneath, so they may be computed after the
  // muscle's own distance and bending projections (finish_muscle_step) with equal result.
  project(m.distances, pos, w);
  project(m.bending, pos, w);
  finish_muscle_step(m, c, skull, pos, w, s, grad);
}

void finish_muscle_step(const Muscle& m, double c, const Points& skull, Points& pos,
                        const std::vector<double>& w, MuscleScratch& s, Points& grad) {
  muscle_targets(m, c, skull, pos, s);
  project(m.volume, pos, w, grad);
  project(m.attach, pos, w, s.targets);
}

}  // namespace facectl::face
