#include "facectl/face/packed_points.hpp"

namespace facectl::face {

void pack(const Points& p, const std::vector<double>& w, PackedPoints& out) {
  const std::size_t n = p.size();
  if (out.q.size() != n) out.q.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.q[i] = {p.x[i], p.y[i], p.z[i], w[i]};
}

void unpack(const PackedPoints& in, Points& out) {
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    out.x[i] = in.q[i].x;
    out.y[i] = in.q[i].y;
    out.z[i] = in.q[i].z;
  }
}

}  // namespace facectl::face
