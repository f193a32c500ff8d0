// The signed dihedral angle's terms (internal header), shared by the bending projection
// and the rest-angle measurement so that a bending constraint is exactly 0 at rest.
#pragma once

#include <cmath>

#include "facectl/face/points.hpp"

namespace facectl::face {

// From e = pb − pa, u = pc − pa, v = pd − pa: the wing normals n1 = e×u and n2 = e×v, their
// squared lengths and dot product, |e|², |e| and 1/|e|², r = 1/(|n1||n2|), and
// cos φ = n̂1·n̂2, sin φ = (n̂1×n̂2)·ê = −(u·n2)|e|·r (because (e×u)×(e×v) = (e·(u×v))e).
struct Dihedral {
  double n1x, n1y, n1z, n2x, n2y, n2z, N1, N2, E, D, r, le, invE, cos, sin;
  bool valid;
};

__attribute__((always_inline)) inline Dihedral dihedral_terms(double ex, double ey, double ez,
                                                              double ux, double uy, double uz,
                                                              double vx, double vy, double vz) {
  Dihedral h;
  h.n1x = ey * uz - ez * uy, h.n1y = ez * ux - ex * uz, h.n1z = ex * uy - ey * ux;
  h.n2x = ey * vz - ez * vy, h.n2y = ez * vx - ex * vz, h.n2z = ex * vy - ey * vx;
  h.N1 = h.n1x * h.n1x + h.n1y * h.n1y + h.n1z * h.n1z;
  h.N2 = h.n2x * h.n2x + h.n2y * h.n2y + h.n2z * h.n2z;
  h.E = ex * ex + ey * ey + ez * ez;
  h.D = h.n1x * h.n2x + h.n1y * h.n2y + h.n1z * h.n2z;
  // Branch-free (the batched projection vectorises it): a degenerate pair (a zero-area
  // wing, a zero-length edge) computes with stand-in lengths and reports !valid.
  h.valid = (h.N1 >= 1e-28) & (h.N2 >= 1e-28) & (h.E >= 1e-20);
  const double N1 = h.valid ? h.N1 : 1.0, N2 = h.valid ? h.N2 : 1.0, E = h.valid ? h.E : 1.0;
  const double R = std::sqrt(N1 * N2);
  h.le = std::sqrt(E);
  const double q = 1 / (R * E);  // one division for 1/R and 1/E
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
