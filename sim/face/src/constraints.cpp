#include "facectl/face/constraints.hpp"

#include <algorithm>
#include <cmath>

namespace facectl::face {

void DistanceConstraints::add(int ia, int ib, double r, double stiffness) {
  a.push_back(ia);
  b.push_back(ib);
  rest.push_back(r);
  k.push_back(stiffness);
}
void BendingConstraints::add(int ia, int ib, int ic, int id, double r, double stiffness) {
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  d.push_back(id);
  rest.push_back(r);
  k.push_back(stiffness);
}
void AreaConstraints::add(int ia, int ib, int ic, double r, double stiffness) {
  a.push_back(ia);
  b.push_back(ib);
  c.push_back(ic);
  rest.push_back(r);
  k.push_back(stiffness);
}
void Attachments::add(int i, double stiffness) {
  particle.push_back(i);
  k.push_back(stiffness);
}

double distance_value(const DistanceConstraints& s, std::size_t i, const Points& p) {
  return (p.get(s.a[i]) - p.get(s.b[i])).norm() - s.rest[i];
}

double bending_angle(const Points& p, int a, int b, int c, int d) {
  Vec3 p1 = p.get(a), e = p.get(b) - p1;
  Vec3 n1 = e.cross(p.get(c) - p1), n2 = e.cross(p.get(d) - p1);
  double l1 = n1.norm(), l2 = n2.norm();
  if (l1 == 0 || l2 == 0) return 0;
  return std::acos(std::clamp(n1.dot(n2) / (l1 * l2), -1.0, 1.0));
}

double area_value(const AreaConstraints& s, std::size_t i, const Points& p) {
  Vec3 p1 = p.get(s.a[i]);
  return 0.5 * (p.get(s.b[i]) - p1).cross(p.get(s.c[i]) - p1).norm() - s.rest[i];
}

double volume_of(const VolumeConstraint& v, const Points& p) {
  double sum = 0;
  for (const Tri& t : v.tris)
    sum += (p.get(t[0]) - v.origin).cross(p.get(t[1]) - v.origin).dot(p.get(t[2]) - v.origin);
  return sum;
}

void project(const DistanceConstraints& s, Points& p, const std::vector<double>& w) {
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int ia = s.a[i], ib = s.b[i];
    const double wa = w[ia], wb = w[ib], wsum = wa + wb;
    if (wsum == 0) continue;
    const double dx = p.x[ia] - p.x[ib], dy = p.y[ia] - p.y[ib], dz = p.z[ia] - p.z[ib];
    const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (len < 1e-12) continue;
    // λ = −s: move each end along n by its mass share of the violation (eq. 3.18–3.19).
    const double f = s.k[i] * (len - s.rest[i]) / (len * wsum);
    p.x[ia] -= wa * f * dx;
    p.y[ia] -= wa * f * dy;
    p.z[ia] -= wa * f * dz;
    p.x[ib] += wb * f * dx;
    p.y[ib] += wb * f * dy;
    p.z[ib] += wb * f * dz;
  }
}

void project(const BendingConstraints& s, Points& p, const std::vector<double>& w) {
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int ia = s.a[i], ib = s.b[i], ic = s.c[i], id = s.d[i];
    // Müller 2006 appendix A, with p1 moved to the origin.
    const Vec3 p1 = p.get(ia);
    const Vec3 p2 = p.get(ib) - p1, p3 = p.get(ic) - p1, p4 = p.get(id) - p1;
    const Vec3 c23 = p2.cross(p3), c24 = p2.cross(p4);
    const double l23 = c23.norm(), l24 = c24.norm();
    if (l23 < 1e-14 || l24 < 1e-14) continue;
    const Vec3 n1 = c23 / l23, n2 = c24 / l24;
    const double dd = std::clamp(n1.dot(n2), -1.0, 1.0);
    const Vec3 q3 = (p2.cross(n2) + n1.cross(p2) * dd) / l23;
    const Vec3 q4 = (p2.cross(n1) + n2.cross(p2) * dd) / l24;
    const Vec3 q2 =
        -(p3.cross(n2) + n1.cross(p3) * dd) / l23 - (p4.cross(n1) + n2.cross(p4) * dd) / l24;
    const Vec3 q1 = -q2 - q3 - q4;
    const double denom = w[ia] * q1.squaredNorm() + w[ib] * q2.squaredNorm() +
                         w[ic] * q3.squaredNorm() + w[id] * q4.squaredNorm();
    if (denom < 1e-20) continue;
    // Müller's appendix: Δp_i = −w_i·√(1−d²)·(acos d − φ)/Σ_j w_j|q_j|² · q_i (the sign is
    // checked by the "projection reduces |C|" unit test).
    const double f = -s.k[i] * std::sqrt(1 - dd * dd) * (std::acos(dd) - s.rest[i]) / denom;
    p.add(ia, f * w[ia] * q1);
    p.add(ib, f * w[ib] * q2);
    p.add(ic, f * w[ic] * q3);
    p.add(id, f * w[id] * q4);
  }
}

namespace {

template <bool kSigned>
void project_area(const AreaConstraints& s, Points& p, const std::vector<double>& w,
                  const Points* ref, const std::vector<double>* rest_sign) {
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int ia = s.a[i], ib = s.b[i], ic = s.c[i];
    const Vec3 p1 = p.get(ia), e1 = p.get(ib) - p1, e2 = p.get(ic) - p1;
    const Vec3 cr = e1.cross(e2);
    const double len = cr.norm();
    if (len < 1e-14) continue;
    const Vec3 nh = cr / len;
    double sign = 1;
    if constexpr (kSigned) {
      // rest_sign 0: the reference was too oblique at rest to tell the sides apart.
      const double rs = (*rest_sign)[i];
      sign = rs != 0 && cr.dot(ref->get(ia)) * rs < -0.5 * len ? -1 : 1;
    }
    const Vec3 g2 = 0.5 * e2.cross(nh), g3 = 0.5 * nh.cross(e1), g1 = -(g2 + g3);
    const double denom =
        w[ia] * g1.squaredNorm() + w[ib] * g2.squaredNorm() + w[ic] * g3.squaredNorm();
    if (denom < 1e-20) continue;
    // ∇(sign·A) = sign·g, so Δp = −k·(sign·A − A0)·sign·g/Σw|g|².
    const double f = -s.k[i] * (sign * 0.5 * len - s.rest[i]) * sign / denom;
    p.add(ia, f * w[ia] * g1);
    p.add(ib, f * w[ib] * g2);
    p.add(ic, f * w[ic] * g3);
  }
}

}  // namespace

void project(const AreaConstraints& s, Points& p, const std::vector<double>& w) {
  project_area<false>(s, p, w, nullptr, nullptr);
}

void project_signed(const AreaConstraints& s, Points& p, const std::vector<double>& w,
                    const Points& ref_normal, const std::vector<double>& rest_sign) {
  project_area<true>(s, p, w, &ref_normal, &rest_sign);
}

void project(const VolumeConstraint& v, Points& p, const std::vector<double>& w, Points& grad) {
  if (v.k == 0) return;
  for (int i : v.verts) grad.set(i, Vec3::Zero());
  double vol = 0;
  for (const Tri& t : v.tris) {
    const Vec3 a = p.get(t[0]) - v.origin, b = p.get(t[1]) - v.origin, c = p.get(t[2]) - v.origin;
    vol += a.cross(b).dot(c);
    grad.add(t[0], b.cross(c));
    grad.add(t[1], c.cross(a));
    grad.add(t[2], a.cross(b));
  }
  double denom = 0;
  for (int i : v.verts) denom += w[i] * grad.get(i).squaredNorm();
  if (denom < 1e-30) return;
  const double f = -v.k * (vol - v.rest) / denom;
  for (int i : v.verts) p.add(i, f * w[i] * grad.get(i));
}

void project(const Attachments& s, Points& p, const std::vector<double>& w, const Points& targets) {
  const std::size_t n = s.size();
  for (std::size_t j = 0; j < n; ++j) {
    const int i = s.particle[j];
    if (w[i] == 0) continue;
    const double k = s.k[j];
    p.x[i] += k * (targets.x[j] - p.x[i]);
    p.y[i] += k * (targets.y[j] - p.y[i]);
    p.z[i] += k * (targets.z[j] - p.z[i]);
  }
}

void add_edge_distances(DistanceConstraints& s, const Points& p, const std::vector<Tri>& tris,
                        double k) {
  for (Edge e : unique_edges(tris)) s.add(e.a, e.b, (p.get(e.a) - p.get(e.b)).norm(), k);
}

void add_bending(BendingConstraints& s, const Points& p, const std::vector<Tri>& tris, double k) {
  for (EdgePair e : interior_edge_pairs(tris))
    s.add(e.a, e.b, e.c, e.d, bending_angle(p, e.a, e.b, e.c, e.d), k);
}

void add_areas(AreaConstraints& s, const Points& p, const std::vector<Tri>& tris, double k) {
  for (const Tri& t : tris) {
    s.add(t[0], t[1], t[2], 0, k);
    s.rest.back() = area_value(s, s.size() - 1, p);
  }
}

VolumeConstraint make_volume(const Points& p, const std::vector<Tri>& tris, const Vec3& origin,
                             double k) {
  VolumeConstraint v;
  v.tris = tris;
  for (const Tri& t : tris) v.verts.insert(v.verts.end(), t.begin(), t.end());
  std::sort(v.verts.begin(), v.verts.end());
  v.verts.erase(std::unique(v.verts.begin(), v.verts.end()), v.verts.end());
  v.origin = origin;
  v.k = k;
  v.rest = volume_of(v, p);
  return v;
}

}  // namespace facectl::face
