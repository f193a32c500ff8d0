// PBD constraint sets in structure-of-arrays form and their Gauss-Seidel projections
// (thesis §3.2, with the errata of reference/face-model-pbd.md §11 applied: λ = −s,
// C_stretch = |p1−p2| − d). Each projection walks its set in index order and moves the
// particles at once, so a fixed set order gives bit-identical results. Stiffness k
// scales each correction (thesis L1165); w are inverse masses.
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
  void add(int ia, int ib, double r, double stiffness);
  std::size_t size() const { return a.size(); }
};

// C = acos(n1·n2) − rest for triangles (a,b,c) and (a,b,d) sharing edge ab (eq. 3.20),
// with n1 = (pb−pa)×(pc−pa), n2 = (pb−pa)×(pd−pa) normalised; gradient from Müller 2006.
struct BendingConstraints {
  std::vector<int> a, b, c, d;
  std::vector<double> rest, k;
  void add(int ia, int ib, int ic, int id, double r, double stiffness);
  std::size_t size() const { return a.size(); }
};

// C = ½|(pb−pa)×(pc−pa)| − rest (eq. 3.21).
struct AreaConstraints {
  std::vector<int> a, b, c;
  std::vector<double> rest, k;
  void add(int ia, int ib, int ic, double r, double stiffness);
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
double bending_angle(const Points& p, int a, int b, int c, int d);
double area_value(const AreaConstraints& s, std::size_t i, const Points& p);
double volume_of(const VolumeConstraint& v, const Points& p);

void project(const DistanceConstraints& s, Points& p, const std::vector<double>& w);
void project(const BendingConstraints& s, Points& p, const std::vector<double>& w);
void project(const AreaConstraints& s, Points& p, const std::vector<double>& w);
// Signed variant: the area counts negative when the triangle's normal opposes
// ref_normal[a] (a per-vertex outward direction) differently than at rest, so an inverted triangle
// is driven back through zero instead of being content at |area| = rest. rest_sign[i] is the sign
// the constraint had at rest (+1 or −1).
void project_signed(const AreaConstraints& s, Points& p, const std::vector<double>& w,
                    const Points& ref_normal, const std::vector<double>& rest_sign);
// `grad` is caller-owned scratch with at least p.size() entries (no allocation here).
void project(const VolumeConstraint& v, Points& p, const std::vector<double>& w, Points& grad);
// targets[j] is the goal of s.particle[j].
void project(const Attachments& s, Points& p, const std::vector<double>& w, const Points& targets);

// Builds the constraint sets of a closed or open triangle surface at its current shape.
void add_edge_distances(DistanceConstraints& s, const Points& p, const std::vector<Tri>& tris,
                        double k);
void add_bending(BendingConstraints& s, const Points& p, const std::vector<Tri>& tris, double k);
void add_areas(AreaConstraints& s, const Points& p, const std::vector<Tri>& tris, double k);
VolumeConstraint make_volume(const Points& p, const std::vector<Tri>& tris, const Vec3& origin,
                             double k);

}  // namespace facectl::face
