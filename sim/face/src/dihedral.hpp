// The signed dihedral angle's terms (internal header), shared by the bending projection
// and the rest-angle measurement so that a bending constraint is exactly 0 at rest.
#pragma once

#include <cmath>

#include "facectl/face/points.hpp"

namespace facectl::face {

// From e = pb − pa, u = pc − pa, v = pd − pa: the wing normals n1 = e×u and n2 = e×v, their
// squared lengths and dot product, |e|², |e| and 1/|e|², r = 1/(|n1||n2|), and
// cos φ = n̂1·n̂2, sin φ = (n̂1×n̂2)·ê = −(u·n2)|e|·r (because (e×u)×(e×v) = (e·(u×v))e).
// T is double, or float for the skin's batched bending (constraint_projection.cpp), which
// passes lengths scaled to about millimetres and thresholds to match.
template <class T>
struct DihedralT {
  T n1x, n1y, n1z, n2x, n2y, n2z, N1, N2, E, D, r, le, invE, cos, sin;
  bool valid;
};
using Dihedral = DihedralT<double>;

// A wing with |n|² < min_n2 or an edge with |e|² < min_e2 is degenerate.
template <class T>
__attribute__((always_inline)) inline DihedralT<T> dihedral_terms(T ex, T ey, T ez, T ux, T uy,
                                                                  T uz, T vx, T vy, T vz,
                                                                  T min_n2 = T(1e-28),
                                                                  T min_e2 = T(1e-20)) {
  DihedralT<T> h;
  h.n1x = ey * uz - ez * uy, h.n1y = ez * ux - ex * uz, h.n1z = ex * uy - ey * ux;
  h.n2x = ey * vz - ez * vy, h.n2y = ez * vx - ex * vz, h.n2z = ex * vy - ey * vx;
  h.N1 = h.n1x * h.n1x + h.n1y * h.n1y + h.n1z * h.n1z;
  h.N2 = h.n2x * h.n2x + h.n2y * h.n2y + h.n2z * h.n2z;
  h.E = ex * ex + ey * ey + ez * ez;
  h.D = h.n1x * h.n2x + h.n1y * h.n2y + h.n1z * h.n2z;
  // Branch-free (the batched projection vectorises it): a degenerate pair (a zero-area
  // wing, a zero-length edge) computes with stand-in lengths and reports !valid.
  h.valid = (h.N1 >= min_n2) & (h.N2 >= min_n2) & (h.E >= min_e2);
  const T N1 = h.valid ? h.N1 : T(1), N2 = h.valid ? h.N2 : T(1), E = h.valid ? h.E : T(1);
  const T R = std::sqrt(N1 * N2);
  h.le = std::sqrt(E);
  const T q = 1 / (R * E);  // one division for 1/R and 1/E
  h.r = q * E;
  h.invE = q * R;
  h.cos = h.D * h.r;
  h.sin = -(ux * h.n2x + uy * h.n2y + uz * h.n2z) * h.le * h.r;
  return h;
}

inline Dihedral dihedral(const Points& p, int a, int b, int c, int d) {
  const Vec3 pa = p.get(a), e = p.get(b) - pa, u = p.get(c) - pa, v = p.get(d) - pa;
  return dihedral_terms(e.x(), e.y(), e.z(), u.x(), u.y(), u.z(), v.x(), v.y(), v.z());
}

}  // namespace facectl::face
