#include "facectl/face/face_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace facectl::face {
namespace {

using Rgb = std::array<double, 3>;

struct Canvas {
  int w, h;
  std::vector<double> depth;
  Image img;
  Canvas(int width, int height)
      : w(width),
        h(height),
        depth(static_cast<std::size_t>(width) * height, -std::numeric_limits<double>::infinity()),
        img(width, height, 0) {
    for (int y = 0; y < h; ++y)  // soft vertical background gradient
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          img.rgb[3 * (y * w + x) + c] = static_cast<std::uint8_t>(70 + 40 * y / h + 10 * c);
  }
};

struct Camera {
  Mat3 R;  // world → view
  Vec3 centre;
  double scale;  // pixels per metre
  int w, h;
  Vec3 project(const Vec3& p) const {  // screen x, y (pixels) and depth (toward viewer +)
    const Vec3 v = R * (p - centre);
    return {w / 2.0 + v.x() * scale, h / 2.0 - v.y() * scale, v.z()};
  }
};

const Vec3 kLight = Vec3(-0.35, 0.45, 1.0).normalized();

double shade(const Vec3& view_normal) {
  return 0.22 + 0.78 * std::abs(view_normal.dot(kLight));  // two-sided Lambert
}

void triangle(Canvas& c, const Camera& cam, const Vec3 p[3], const Vec3 n[3], const Rgb& col) {
  Vec3 s[3];
  double I[3];
  for (int k = 0; k < 3; ++k) {
    s[k] = cam.project(p[k]);
    I[k] = shade(cam.R * n[k]);
  }
  const double area =
      (s[1].x() - s[0].x()) * (s[2].y() - s[0].y()) - (s[2].x() - s[0].x()) * (s[1].y() - s[0].y());
  if (std::abs(area) < 1e-12) return;
  const int x0 =
      std::max(0, static_cast<int>(std::floor(std::min({s[0].x(), s[1].x(), s[2].x()}))));
  const int x1 =
      std::min(c.w - 1, static_cast<int>(std::ceil(std::max({s[0].x(), s[1].x(), s[2].x()}))));
  const int y0 =
      std::max(0, static_cast<int>(std::floor(std::min({s[0].y(), s[1].y(), s[2].y()}))));
  const int y1 =
      std::min(c.h - 1, static_cast<int>(std::ceil(std::max({s[0].y(), s[1].y(), s[2].y()}))));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double b0 =
          ((s[1].x() - px) * (s[2].y() - py) - (s[2].x() - px) * (s[1].y() - py)) / area;
      const double b1 =
          ((s[2].x() - px) * (s[0].y() - py) - (s[0].x() - px) * (s[2].y() - py)) / area;
      const double b2 = 1 - b0 - b1;
      if (b0 < 0 || b1 < 0 || b2 < 0) continue;
      const double z = b0 * s[0].z() + b1 * s[1].z() + b2 * s[2].z();
      const std::size_t i = static_cast<std::size_t>(y) * c.w + x;
      if (z <= c.depth[i]) continue;
      c.depth[i] = z;
      const double light = b0 * I[0] + b1 * I[1] + b2 * I[2];
      for (int k = 0; k < 3; ++k)
        c.img.rgb[3 * i + k] = static_cast<std::uint8_t>(std::clamp(col[k] * light, 0.0, 255.0));
    }
}

void mesh(Canvas& c, const Camera& cam, const Points& v, const std::vector<Tri>& tris,
          const Rgb& col) {
  Points n;
  vertex_normals(v, tris, n);
  for (const Tri& t : tris) {
    const Vec3 p[3] = {v.get(t[0]), v.get(t[1]), v.get(t[2])};
    const Vec3 nn[3] = {n.get(t[0]), n.get(t[1]), n.get(t[2])};
    triangle(c, cam, p, nn, col);
  }
}

void flat_tris(Canvas& c, const Camera& cam, const std::vector<Vec3>& pts,
               const std::vector<Tri>& tris, const Rgb& col) {
  for (const Tri& t : tris) {
    const Vec3 p[3] = {pts[t[0]], pts[t[1]], pts[t[2]]};
    Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
    const Vec3 nn[3] = {n, n, n};
    triangle(c, cam, p, nn, col);
  }
}

// Eyeball: a UV sphere, white with an iris and pupil around the gaze direction (+z).
void eyeball(Canvas& c, const Camera& cam, const Vec3& centre, double r) {
  const int nl = 16, nm = 24;
  auto at = [&](int i, int j) {
    const double th = std::numbers::pi * i / nl, ph = 2 * std::numbers::pi * j / nm;
    return Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  };
  for (int i = 0; i < nl; ++i)
    for (int j = 0; j < nm; ++j) {
      const Vec3 a = at(i, j), b = at(i + 1, j), d = at(i + 1, j + 1), e = at(i, j + 1);
      const double gaze = ((a + d) / 2).normalized().z();
      const Rgb col = gaze > 0.97   ? Rgb{20, 15, 10}
                      : gaze > 0.88 ? Rgb{95, 70, 45}
                                    : Rgb{235, 232, 225};
      for (const auto& q : {std::array<Vec3, 3>{a, b, d}, std::array<Vec3, 3>{a, d, e}}) {
        const Vec3 p[3] = {centre + r * q[0], centre + r * q[1], centre + r * q[2]};
        triangle(c, cam, p, q.data(), col);
      }
    }
}

}  // namespace

Image render_face(const FaceModel& m, const FaceData& d, const RenderOptions& o) {
  const int ss = 2;
  Canvas c(o.width * ss, o.height * ss);
  Vec3 lo = m.skin.v.get(0), hi = lo;
  for (std::size_t i = 0; i < m.skin.v.size(); ++i) {
    lo = lo.cwiseMin(m.skin.v.get(i));
    hi = hi.cwiseMax(m.skin.v.get(i));
  }
  const double yaw = o.view == View::kFront ? 0 : o.view == View::kSide ? -90 : -35;
  Camera cam{rodrigues(Vec3::UnitY(), yaw * std::numbers::pi / 180), 0.5 * (lo + hi), 0, c.w, c.h};
  // Fit the rotated rest bounding box into the picture with a small margin.
  double ex = 0, ey = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                      (k & 4) ? hi.z() : lo.z());
    const Vec3 v = cam.R * (corner - cam.centre);
    ex = std::max(ex, std::abs(v.x()));
    ey = std::max(ey, std::abs(v.y()));
  }
  cam.scale = 0.94 * std::min(c.w / (2 * ex), c.h / (2 * ey));
  if (o.muscles) {
    mesh(c, cam, d.skull, m.skull.tris, {225, 215, 190});
    for (const Muscle& mu : m.muscles) {
      const bool passive = m.command_slot[&mu - m.muscles.data()] < 0;
      mesh(c, cam, d.muscles, mu.surface, passive ? Rgb{230, 200, 120} : Rgb{200, 60, 55});
    }
  } else {
    mesh(c, cam, d.skin_x, m.skin.tris, {236, 188, 160});
    for (const EyelidSide& e : m.eyes) eyeball(c, cam, e.axis_point, 0.95 * m.spec.eyeball_radius);
    flat_tris(c, cam, m.upper_teeth.points, m.upper_teeth.tris, {245, 242, 230});
    flat_tris(c, cam, d.lower_teeth.points, d.lower_teeth.tris, {245, 242, 230});
    // Mouth cavity: a dark disc behind the teeth.
    const Vec3 centre =
        0.5 * (m.upper_teeth.box_min + m.upper_teeth.box_max) - Vec3(0, 0.004, 0.01);
    std::vector<Vec3> disc{centre};
    std::vector<Tri> fan;
    for (int k = 0; k < 24; ++k) {
      const double a = 2 * std::numbers::pi * k / 24;
      disc.push_back(centre + Vec3(0.032 * std::cos(a), 0.03 * std::sin(a), 0));
      fan.push_back({0, 1 + k, 1 + (k + 1) % 24});
    }
    flat_tris(c, cam, disc, fan, {70, 25, 30});
  }
  return downsample(c.img, ss);
}

}  // namespace facectl::face
