#include "facectl/face/face_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "facectl/face/heat_map.hpp"

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
// Raking key light in view space: from above and to the left, about 68° off the view axis,
// so it grazes a face turned toward the camera.
const Vec3 kKey = Vec3(-0.45, 0.8, 0.38).normalized();
// Darkening per unit of valley curvature (m): a crease of 5 mm radius (200/m) darkens
// by 0.3, the most allowed is 0.4.
constexpr double kCavityDepth = 0.0015;
const Vec3 kHalf = (kKey + Vec3::UnitZ()).normalized();  // Blinn half vector, viewer on +z

// Colour of a vertex with albedo `col` and view-space normal n.
Rgb lit(const RenderOptions& o, const Vec3& n_view, const Rgb& col, bool heat) {
  if (o.lighting == Lighting::kFrontal) {
    const double I = 0.22 + 0.78 * std::abs(n_view.dot(kLight));  // two-sided Lambert
    return {col[0] * I, col[1] * I, col[2] * I};
  }
  const Vec3 n = n_view.z() < 0 ? -n_view : n_view;  // the side facing the camera
  const double key = std::max(0.0, n.dot(kKey)), fill = std::max(0.0, n.z());
  if (heat) {  // keep the hue readable: shading only modulates brightness gently
    const double I = 0.55 + 0.3 * key + 0.2 * fill;
    return {col[0] * I, col[1] * I, col[2] * I};
  }
  const double I = 0.12 + 0.95 * key + 0.28 * fill;
  const double spec = 40 * std::pow(std::max(0.0, n.dot(kHalf)), 30);
  return {col[0] * I + spec, col[1] * I + spec, col[2] * I + spec};
}

void triangle(Canvas& c, const Camera& cam, const Vec3 p[3], const Rgb col[3]) {
  Vec3 s[3];
  for (int k = 0; k < 3; ++k) s[k] = cam.project(p[k]);
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
      for (int k = 0; k < 3; ++k)
        c.img.rgb[3 * i + k] = static_cast<std::uint8_t>(
            std::clamp(b0 * col[0][k] + b1 * col[1][k] + b2 * col[2][k], 0.0, 255.0));
    }
}

// One colour per vertex (albedo), lit per vertex and interpolated (Gouraud).
void mesh(Canvas& c, const Camera& cam, const RenderOptions& o, const Points& v,
          const std::vector<Tri>& tris, const std::vector<Rgb>& albedo, bool heat) {
  Points n;
  vertex_normals(v, tris, n);
  std::vector<Rgb> col(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    col[i] = lit(o, cam.R * n.get(i), albedo.size() == 1 ? albedo[0] : albedo[i], heat);
  for (const Tri& t : tris) {
    const Vec3 p[3] = {v.get(t[0]), v.get(t[1]), v.get(t[2])};
    const Rgb cc[3] = {col[t[0]], col[t[1]], col[t[2]]};
    triangle(c, cam, p, cc);
  }
}

void mesh(Canvas& c, const Camera& cam, const RenderOptions& o, const Points& v,
          const std::vector<Tri>& tris, const Rgb& col) {
  mesh(c, cam, o, v, tris, std::vector<Rgb>{col}, false);
}

void flat_tris(Canvas& c, const Camera& cam, const RenderOptions& o, const std::vector<Vec3>& pts,
               const std::vector<Tri>& tris, const Rgb& col) {
  for (const Tri& t : tris) {
    const Vec3 p[3] = {pts[t[0]], pts[t[1]], pts[t[2]]};
    const Rgb l = lit(o, cam.R * (p[1] - p[0]).cross(p[2] - p[0]).normalized(), col, false);
    const Rgb cc[3] = {l, l, l};
    triangle(c, cam, p, cc);
  }
}

// Eyeball: a UV sphere, white with an iris and pupil around the gaze direction (+z).
void eyeball(Canvas& c, const Camera& cam, const RenderOptions& o, const Vec3& centre, double r,
             bool grey) {
  const int nl = 16, nm = 24;
  auto at = [&](int i, int j) {
    const double th = std::numbers::pi * i / nl, ph = 2 * std::numbers::pi * j / nm;
    return Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  };
  for (int i = 0; i < nl; ++i)
    for (int j = 0; j < nm; ++j) {
      const Vec3 a = at(i, j), b = at(i + 1, j), d = at(i + 1, j + 1), e = at(i, j + 1);
      const double gaze = ((a + d) / 2).normalized().z();
      const Rgb col = grey          ? Rgb{150, 150, 150}
                      : gaze > 0.97 ? Rgb{20, 15, 10}
                      : gaze > 0.88 ? Rgb{95, 70, 45}
                                    : Rgb{235, 232, 225};
      for (const auto& q : {std::array<Vec3, 3>{a, b, d}, std::array<Vec3, 3>{a, d, e}}) {
        const Vec3 p[3] = {centre + r * q[0], centre + r * q[1], centre + r * q[2]};
        const Rgb cc[3] = {lit(o, cam.R * q[0], col, false), lit(o, cam.R * q[1], col, false),
                           lit(o, cam.R * q[2], col, false)};
        triangle(c, cam, p, cc);
      }
    }
}

// A cheap stand-in for ambient occlusion: each vertex darkened by how deep it sits in a
// valley, from the umbrella Laplacian along the normal (≈ mean curvature × edge² / 2).
// Fold bottoms and creases go dark; ridges and flat skin keep their colour.
std::vector<double> cavity_darkening(const Points& v, const std::vector<Tri>& tris) {
  const Adjacency adj = vertex_adjacency(v.size(), tris);
  Points n;
  vertex_normals(v, tris, n);
  std::vector<double> out(v.size(), 1.0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const int a = adj.start[i], b = adj.start[i + 1];
    if (a == b) continue;
    Vec3 mean = Vec3::Zero();
    double e2 = 0;
    for (int k = a; k < b; ++k) {
      mean += v.get(adj.nbr[k]);
      e2 += (v.get(adj.nbr[k]) - v.get(i)).squaredNorm();
    }
    mean /= b - a;
    e2 /= b - a;
    if (!(e2 > 0)) continue;  // all neighbours on the vertex: no curvature to shade
    const double curvature = 2 * (mean - v.get(i)).dot(n.get(i)) / e2;  // 1/m, + in valleys
    out[i] = 1 - std::clamp(kCavityDepth * curvature, 0.0, 0.4);
  }
  return out;
}

Camera make_camera(const FaceModel& m, View view, int w, int h) {
  Vec3 lo = m.skin.v.get(0), hi = lo;
  for (std::size_t i = 0; i < m.skin.v.size(); ++i) {
    lo = lo.cwiseMin(m.skin.v.get(i));
    hi = hi.cwiseMax(m.skin.v.get(i));
  }
  const double yaw = view == View::kFront ? 0 : view == View::kSide ? -90 : -35;
  Camera cam{rodrigues(Vec3::UnitY(), yaw * std::numbers::pi / 180), 0.5 * (lo + hi), 0, w, h};
  // Fit the rotated rest bounding box into the picture with a small margin.
  double ex = 0, ey = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                      (k & 4) ? hi.z() : lo.z());
    const Vec3 v = cam.R * (corner - cam.centre);
    ex = std::max(ex, std::abs(v.x()));
    ey = std::max(ey, std::abs(v.y()));
  }
  cam.scale = 0.94 * std::min(w / (2 * ex), h / (2 * ey));
  return cam;
}

constexpr int kSupersample = 2;

}  // namespace

Eigen::Vector2d project_to_image(const FaceModel& m, const RenderOptions& o, const Vec3& p) {
  const Camera cam = make_camera(m, o.view, o.width * kSupersample, o.height * kSupersample);
  const Vec3 s = cam.project(p);
  return {s.x() / kSupersample, s.y() / kSupersample};
}

Image render_face(const FaceModel& m, const FaceData& d, const RenderOptions& o) {
  if (o.width < 16 || o.width > 8192 || o.height < 16 || o.height > 8192)
    throw std::invalid_argument("render: picture size " + std::to_string(o.width) + "x" +
                                std::to_string(o.height) + " is outside 16..8192 pixels");
  if (o.heat_mm && o.heat_mm->size() != d.skin_x.size())
    throw std::invalid_argument("render: heat map has " + std::to_string(o.heat_mm->size()) +
                                " values for " + std::to_string(d.skin_x.size()) +
                                " skin vertices");
  if (o.heat_mm && !(o.heat_max_mm > 0))
    throw std::invalid_argument("render: heat map scale must be positive, not " +
                                std::to_string(o.heat_max_mm) + " mm");
  const int ss = kSupersample;
  Canvas c(o.width * ss, o.height * ss);
  const Camera cam = make_camera(m, o.view, c.w, c.h);
  if (o.muscles) {
    mesh(c, cam, o, d.skull, m.skull.tris, {225, 215, 190});
    for (const Muscle& mu : m.muscles) {
      const bool passive = m.command_slot[&mu - m.muscles.data()] < 0;
      mesh(c, cam, o, d.muscles, mu.surface, passive ? Rgb{230, 200, 120} : Rgb{200, 60, 55});
    }
    return downsample(c.img, ss);
  }
  const bool heat = o.heat_mm != nullptr;
  if (heat) {
    std::vector<Rgb> albedo(d.skin_x.size());
    for (std::size_t i = 0; i < albedo.size(); ++i) {
      const Rgb8 h = heat_colour((*o.heat_mm)[i] / o.heat_max_mm);
      albedo[i] = {double(h[0]), double(h[1]), double(h[2])};
    }
    mesh(c, cam, o, d.skin_x, m.skin.tris, albedo, true);
  } else {
    std::vector<Rgb> albedo(d.skin_x.size(), Rgb{236, 188, 160});
    if (o.lighting == Lighting::kRaking) {
      const std::vector<double> dark = cavity_darkening(d.skin_x, m.skin.tris);
      for (std::size_t i = 0; i < albedo.size(); ++i)
        for (double& ch : albedo[i]) ch *= dark[i];
    }
    mesh(c, cam, o, d.skin_x, m.skin.tris, albedo, false);
  }
  for (const EyelidSide& e : m.eyes)
    eyeball(c, cam, o, e.axis_point, 0.95 * m.spec.eyeball_radius, heat);
  const Rgb teeth = heat ? Rgb{150, 150, 150} : Rgb{245, 242, 230};
  flat_tris(c, cam, o, m.upper_teeth.points, m.upper_teeth.tris, teeth);
  flat_tris(c, cam, o, d.lower_teeth.points, d.lower_teeth.tris, teeth);
  // Mouth cavity: a dark disc behind the teeth.
  const Vec3 centre = 0.5 * (m.upper_teeth.box_min + m.upper_teeth.box_max) - Vec3(0, 0.004, 0.01);
  std::vector<Vec3> disc{centre};
  std::vector<Tri> fan;
  for (int k = 0; k < 24; ++k) {
    const double a = 2 * std::numbers::pi * k / 24;
    disc.push_back(centre + Vec3(0.032 * std::cos(a), 0.03 * std::sin(a), 0));
    fan.push_back({0, 1 + k, 1 + (k + 1) % 24});
  }
  flat_tris(c, cam, o, disc, fan, heat ? Rgb{45, 45, 45} : Rgb{70, 25, 30});
  return downsample(c.img, ss);
}

}  // namespace facectl::face
