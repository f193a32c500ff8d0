#include "facectl/face/heat_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "facectl/face/bitmap_font.hpp"

namespace facectl::face {

std::vector<double> displacement_mm(const Points& a, const Points& b) {
  if (a.size() != b.size())
    throw std::invalid_argument("displacement: " + std::to_string(a.size()) + " against " +
                                std::to_string(b.size()) + " vertices");
  std::vector<double> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = 1000 * (a.get(i) - b.get(i)).norm();
  return out;
}

Rgb8 heat_colour(double t) {
  // Piecewise-linear stops, roughly the "turbo" ramp's hues with a darker zero.
  static constexpr double kStops[][3] = {
      {35, 55, 140}, {30, 150, 210}, {80, 195, 90}, {245, 205, 40}, {215, 40, 30}};
  const double s = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * 4;
  const int k = std::min(3, static_cast<int>(s));
  const double f = s - k;
  Rgb8 c;
  for (int i = 0; i < 3; ++i)
    c[i] = static_cast<std::uint8_t>(std::lround((1 - f) * kStops[k][i] + f * kStops[k + 1][i]));
  return c;
}

Image colour_bar(int width, double max_mm) {
  if (!(max_mm > 0) || !std::isfinite(max_mm))
    throw std::invalid_argument("colour bar: the scale must be a positive number of mm, not " +
                                std::to_string(max_mm));
  if (width < 120)
    throw std::invalid_argument("colour bar: needs at least 120 pixels, not " +
                                std::to_string(width));
  const std::string caption = "|displacement from neutral| in mm";
  const int scale = text_width(caption, 2) + 16 <= width ? 2 : 1;
  const int line = scale * (kGlyphHeight + 3), margin = 8 * scale;
  const int bar_x = margin, bar_w = width - 2 * margin, bar_y = line + 2, bar_h = line;
  Image img(width, bar_y + bar_h + 4 + line + 2, 255);
  const Rgb8 ink{30, 30, 30};
  draw_text(img, (width - text_width(caption, scale)) / 2, 2, caption, scale, ink);
  for (int x = 0; x < bar_w; ++x) {
    const Rgb8 c = heat_colour(x / (bar_w - 1.0));
    for (int y = 0; y < bar_h; ++y)
      std::copy(c.begin(), c.end(), &img.rgb[3 * ((bar_y + y) * width + bar_x + x)]);
  }
  // Ticks at a 1-2-5 step giving at most five intervals.
  double step = std::pow(10.0, std::floor(std::log10(max_mm)));
  for (double m : {0.1, 0.2, 0.5, 1.0, 2.0, 5.0})
    if (max_mm / (step * m) <= 5) {
      step *= m;
      break;
    }
  for (int k = 0; k * step <= max_mm * (1 + 1e-9); ++k) {
    const int x = bar_x + static_cast<int>(std::lround(k * step / max_mm * (bar_w - 1)));
    for (int y = bar_y + bar_h; y < bar_y + bar_h + 3; ++y)
      for (int dx = 0; dx < scale; ++dx)
        std::copy(ink.begin(), ink.end(), &img.rgb[3 * (y * width + std::min(width - 1, x + dx))]);
    char label[32];
    std::snprintf(label, sizeof label, "%g", k * step);
    const int lw = text_width(label, scale);
    draw_text(img, std::clamp(x - lw / 2, 0, width - lw), bar_y + bar_h + 4, label, scale, ink);
  }
  return img;
}

}  // namespace facectl::face
