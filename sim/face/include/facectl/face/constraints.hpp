// PBD constraint sets in structure-of-arrays form and their Gauss-Seidel projections
// (thesis §3.2, with two errata corrected: λ = −s, and
// C_stretch = |p1−p2| − d). Each projection walks its set in index order and moves the
// particles at once, so a fixed set order gives bit-identical results. Stiffness k
// scales each correction (thesis); w are inverse masses.
#pragma once

#include <cstddef>
#include <vector>

#include "facectl/face/mesh.hpp"
#include "facectl/face/points.hpp"

namespace facectl::face {

// C = |pa − pb| − rest (eqs. 3.15–3.19).
struct DistanceConstraints {
  std::vector<int> a, b;
  std::vector<double> rest, k;
  std::vector<int> runs;  // see order_in_runs(); empty: one constraint at a time
  void add(int ia, int ib, double r, double stiffness);
  std::size_t size() const { return a.size(); }
};

// Signed dihedral angle of triangles (a,b,c) and (a,b,d) sharing edge ab (eq. 3.20 with a
// sign): φ is the angle from n1 = e×(pc−pa) to n2 = e×(pd−pa) about e = pb−pa, in (−π, π]
// (|φ| is the thesis's acos(n̂1·n̂2); a flat pair has |φ| = π). C = φ − rest, with the
// exact gradient of Bridson, Marino and Fedkiw (2003) instead of Müller 2006's acos form,
// whose correction vanishes at flat and fully folded pairs and which cannot tell a fold
// from its mirror image. cos_rest/sin_rest are the rest angle's cosine and sine; the
// projection evaluates φ − rest from them without trigonometry (docs/FACE_MODEL.md).
struct BendingConstraints {
  std::vector<int> a, b, c, d;
  std::vector<double> rest, cos_rest, sin_rest, k;
  std::vector<int> runs;  // see order_in_runs()
  // Rest angle given in radians (tests, hand-made sets).
  void add(int ia, int ib, int ic, int id, double r, double stiffness);
  // Rest angle measured on `p` (bit-identical to what the projection measures there).
  void add_at_rest(const Points& p, int ia, int ib, int ic, int id, double stiffness);
  std::size_t size() const { return a.size(); }
};

// The stretch of each bending pair's shared edge (a[i], b[i]) of a BendingConstraints,
// so that an edge's stretch and its pair's bending are projected together, stretch first
// (project_with_stretch). Built by split_pair_stretch().
struct PairStretch {
  std::vector<double> rest, k;
};

// C = ½|(pb−pa)×(pc−pa)| − rest (eq. 3.21).
struct AreaConstraints {
  std::vector<int> a, b, c;
  std::vector<double> rest, k;
  std::vector<int> runs;  // see order_in_runs()
  void add(int ia, int ib, int ic, double r, double stiffness);
  std::size_t size() const { return a.size(); }
};

// No-inversion (not in the thesis): C = ((pb−pa)×(pc−pa))·n − min ≥ 0, unilateral, where n
// is the triangle's unit rest normal and min = fraction·2·(rest area): the triangle's area
// projected on its rest normal may not fall below that fraction of its rest area, so it
// cannot turn through 90° (or collapse) without the constraint pushing back. Linear in
// each vertex, so its gradient is exact and cheap: ∇b = (pc−pa)×n, ∇c = n×(pb−pa).
struct OrientationConstraints {
  std::vector<int> a, b, c;
  std::vector<double> nx, ny, nz, min, k;
  std::vector<int> runs;  // see order_in_runs()
  void add(int ia, int ib, int ic, const Vec3& unit_normal, double min_value, double stiffness);
  std::size_t size() const { return a.size(); }
};

// C = Σ_tri ((pa−o)×(pb−o))·(pc−o) − rest over a triangle set (eq. 3.22, no 1/6, as
// printed; consistent because rest is computed the same way). `o` is a fixed reference
// point; for a closed surface the value does not depend on it.
struct VolumeConstraint {
  std::vector<Tri> tris;
  std::vector<int> verts;  // the distinct vertices of tris, ascending
  Vec3 origin{0, 0, 0};
  double rest = 0, k = 0;
};

// Position/attachment C = |p − target| (eq. 3.23), applied as p += k·(target − p).
struct Attachments {
  std::vector<int> particle;
  std::vector<double> k;
  void add(int i, double stiffness);
  std::size_t size() const { return particle.size(); }
};

double distance_value(const DistanceConstraints& s, std::size_t i, const Points& p);
// The signed dihedral angle φ of BendingConstraints, in (−π, π]; 0 when degenerate.
double bending_angle(const Points& p, int a, int b, int c, int d);
double area_value(const AreaConstraints& s, std::size_t i, const Points& p);
double volume_of(const VolumeConstraint& v, const Points& p);

void project(const DistanceConstraints& s, Points& p, const std::vector<double>& w);
void project(const BendingConstraints& s, Points& p, const std::vector<double>& w);
void project(const AreaConstraints& s, Points& p, const std::vector<double>& w);
void project(const OrientationConstraints& s, Points& p, const std::vector<double>& w);
// Projects constraint i alone if it is violated with its bound scaled by floor_scale, onto
// its bound scaled by target_scale ≥ floor_scale (a margin, so that a neighbour's later
// correction does not at once undo it); false (nothing moved) when it is satisfied.
bool project_one(const OrientationConstraints& s, std::size_t i, Points& p,
                 const std::vector<double>& w, double floor_scale = 1.0, double target_scale = 1.0);
// Inline: the end-of-frame untangling scans every skin triangle with it.
inline double orientation_value(const OrientationConstraints& s, std::size_t i, const Points& p,
                                double floor_scale = 1.0) {
  const int a = s.a[i], b = s.b[i], c = s.c[i];
  const double e1x = p.x[b] - p.x[a], e1y = p.y[b] - p.y[a], e1z = p.z[b] - p.z[a];
  const double e2x = p.x[c] - p.x[a], e2y = p.y[c] - p.y[a], e2z = p.z[c] - p.z[a];
  return (e1y * e2z - e1z * e2y) * s.nx[i] + (e1z * e2x - e1x * e2z) * s.ny[i] +
         (e1x * e2y - e1y * e2x) * s.nz[i] - floor_scale * s.min[i];
}
// `grad` is caller-owned scratch with at least p.size() entries (no allocation here).
void project(const VolumeConstraint& v, Points& p, const std::vector<double>& w, Points& grad);
// targets[j] is the goal of s.particle[j].
void project(const Attachments& s, Points& p, const std::vector<double>& w, const Points& targets);

// Fused sweep (docs/FACE_MODEL.md, "Fused edge sweep"): one gather and one store serve an
// edge's stretch (constraint i of `stretch`, on pair i's edge ab) and then its pair's
// bending, one after the other in each lane, which is exactly Gauss–Seidel in the
// interleaved order stretch 0, bending 0, stretch 1, bending 1, ...
void project_with_stretch(const BendingConstraints& s, const PairStretch& stretch, Points& p,
                          const std::vector<double>& w);

// Gauss–Seidel order for batched projection: reorders the set along a Z-order curve
// through the constraints' centroids on `rest` and cuts it into batches of up to 8
// constraints that share no particle, recording the batch ends in `runs`. The projection
// then handles a batch at once, with the same result as one constraint after another in
// the new order. add() clears the runs (back to one at a time): order a complete set.
// Appends `from` to `to` (unordered: order_in_runs the result).
void append(DistanceConstraints& to, const DistanceConstraints& from);
void append(BendingConstraints& to, const BendingConstraints& from);
void order_in_runs(DistanceConstraints& s, const Points& rest);
void order_in_runs(BendingConstraints& s, const Points& rest);
void order_in_runs(AreaConstraints& s, const Points& rest);
void order_in_runs(OrientationConstraints& s, const Points& rest);

// Moves the stretch of every edge that `bending` pairs into a PairStretch aligned with
// `bending` (a pair's edge is a[i]–b[i]; an edge shared by several pairs rides with the
// first, the others get k = 0); `edges` keeps the unpaired (border) edges, still in runs.
PairStretch split_pair_stretch(DistanceConstraints& edges, const BendingConstraints& bending,
                               const Points& rest);

// Builds the constraint sets of a closed or open triangle surface at its current shape,
// ordered in runs (order_in_runs).
void add_edge_distances(DistanceConstraints& s, const Points& p, const std::vector<Tri>& tris,
                        double k);
void add_bending(BendingConstraints& s, const Points& p, const std::vector<Tri>& tris, double k);
void add_areas(AreaConstraints& s, const Points& p, const std::vector<Tri>& tris, double k);
void add_orientations(OrientationConstraints& s, const Points& p, const std::vector<Tri>& tris,
                      double min_fraction, double k);
VolumeConstraint make_volume(const Points& p, const std::vector<Tri>& tris, const Vec3& origin,
                             double k);

}  // namespace facectl::face
