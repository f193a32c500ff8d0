#include "firmware-host/report/svg_plot.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <system_error>

#include "firmware-host/report/markup_escape.hpp"

namespace facectl {
namespace {

// Two decimals, the same bytes as printf's "%.2f" (std::to_chars is specified
// so), several times faster: a plot writes tens of thousands of coordinates.
std::string num(double v) {
  char buf[32];
  const auto [end, error] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 2);
  if (error == std::errc()) return {buf, end};
  std::string wide(400, '\0');  // |v| ≥ 1e29 (a degenerate axis): printf's full width
  wide.resize(static_cast<std::size_t>(std::snprintf(wide.data(), wide.size(), "%.2f", v)));
  return wide;
}

std::string tick_label(double v, double step) {
  char buf[32];
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step)));
  std::snprintf(buf, sizeof buf, "%.*f", decimals, std::fabs(v) < step * 1e-9 ? 0.0 : v);
  return buf;
}

// A series' points, reduced per pixel column to its first, lowest, highest
// and last point (in time order): small files that keep every peak.
template <typename Px, typename Py>
void write_points(std::ostream& o, const Plot::Series& s, Px px, Py py) {
  const std::size_t n = std::min(s.x.size(), s.y.size());
  std::size_t i = 0;
  while (i < n) {
    const double column = std::floor(px(s.x[i]));
    std::size_t end = i + 1, lo = i, hi = i;
    for (; end < n && std::floor(px(s.x[end])) == column; ++end) {
      if (s.y[end] < s.y[lo]) lo = end;
      if (s.y[end] > s.y[hi]) hi = end;
    }
    std::size_t keep[4] = {i, std::min(lo, hi), std::max(lo, hi), end - 1};
    for (int k = 0; k < 4; ++k) {
      if (k > 0 && keep[k] == keep[k - 1]) continue;
      o << num(px(s.x[keep[k]])) << ',' << num(py(s.y[keep[k]])) << ' ';
    }
    i = end;
  }
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target_count) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, target_count);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step) * step; t <= hi + step * 1e-9; t += step) {
    ticks.push_back(t);
    // A step below the resolution of doubles at t (a range of a few units at
    // 1e16) would never move t: no further tick could differ from this one.
    if (t + step == t) break;
  }
  return ticks;
}

std::string render_svg(const Plot& plot, int width, int height) {
  const double left = 70;
  const double right = 180;  // legend
  const double top = 34;
  const double rows = static_cast<double>(plot.mark_rows.size());
  const double bottom = 46 + 10 * rows;
  const double w = width - left - right;
  const double h = height - top - bottom;

  double x0 = std::numeric_limits<double>::infinity();
  double x1 = -x0;
  double y0 = x0;
  double y1 = -x0;
  for (const auto& s : plot.series) {
    for (double v : s.x) x0 = std::min(x0, v), x1 = std::max(x1, v);
    for (double v : s.y) y0 = std::min(y0, v), y1 = std::max(y1, v);
  }
  for (const auto& l : plot.levels) y0 = std::min(y0, l.y), y1 = std::max(y1, l.y);
  if (!std::isfinite(x0)) x0 = 0, x1 = 1;
  if (!std::isfinite(y0)) y0 = 0, y1 = 1;
  if (x1 <= x0) x1 = x0 + 1;
  if (y1 <= y0) y0 -= 1, y1 += 1;
  const double pad = 0.06 * (y1 - y0);
  y0 -= pad;
  y1 += pad;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * w; };
  auto py = [&](double y) { return top + (1.0 - (y - y0) / (y1 - y0)) * h; };

  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << ' ' << height
    << "\" font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"12\">\n";
  o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o << "<text x=\"" << left << "\" y=\"20\" font-size=\"15\" font-weight=\"bold\">"
    << escape_markup(plot.title) << "</text>\n";
  for (const auto& s : plot.spans) {
    o << "<rect x=\"" << num(px(s.x0)) << "\" y=\"" << top << "\" width=\""
      << num(std::max(0.5, px(s.x1) - px(s.x0))) << "\" height=\"" << h << "\" fill=\"" << s.color
      << "\" fill-opacity=\"0.18\"/>\n";
  }
  for (double t : nice_ticks(y0, y1)) {
    o << "<line x1=\"" << left << "\" x2=\"" << left + w << "\" y1=\"" << num(py(t)) << "\" y2=\""
      << num(py(t)) << "\" stroke=\"#e4e4e4\"/>\n";
    o << "<text x=\"" << left - 6 << "\" y=\"" << num(py(t) + 4) << "\" text-anchor=\"end\">"
      << tick_label(
             t, nice_ticks(y0, y1).size() > 1 ? nice_ticks(y0, y1)[1] - nice_ticks(y0, y1)[0] : 1)
      << "</text>\n";
  }
  const auto xt = nice_ticks(x0, x1, 10);
  for (double t : xt) {
    o << "<line x1=\"" << num(px(t)) << "\" x2=\"" << num(px(t)) << "\" y1=\"" << top << "\" y2=\""
      << top + h << "\" stroke=\"#f0f0f0\"/>\n";
    o << "<text x=\"" << num(px(t)) << "\" y=\"" << top + h + 16 << "\" text-anchor=\"middle\">"
      << tick_label(t, xt.size() > 1 ? xt[1] - xt[0] : 1) << "</text>\n";
  }
  o << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << w << "\" height=\"" << h
    << "\" fill=\"none\" stroke=\"#888\"/>\n";
  for (const auto& l : plot.levels) {
    o << "<line x1=\"" << left << "\" x2=\"" << left + w << "\" y1=\"" << num(py(l.y)) << "\" y2=\""
      << num(py(l.y)) << "\" stroke=\"" << l.color << "\" stroke-width=\"2\""
      << (l.dashed ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
  }
  for (const auto& s : plot.series) {
    o << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"" << s.width
      << "\" points=\"";
    write_points(o, s, px, py);
    o << "\"/>\n";
  }
  for (const auto& m : plot.marks) {
    const double y = top + h + 24 + 10 * m.row;
    o << "<line x1=\"" << num(px(m.x)) << "\" x2=\"" << num(px(m.x)) << "\" y1=\"" << y
      << "\" y2=\"" << y + 7 << "\" stroke=\"" << m.color << "\"/>\n";
  }
  for (std::size_t r = 0; r < plot.mark_rows.size(); ++r) {
    o << "<text x=\"" << left - 6 << "\" y=\"" << top + h + 31 + 10 * static_cast<double>(r)
      << "\" text-anchor=\"end\" font-size=\"9\">" << escape_markup(plot.mark_rows[r])
      << "</text>\n";
  }
  o << "<text x=\"" << left + w / 2 << "\" y=\"" << height - 6 << "\" text-anchor=\"middle\">"
    << escape_markup(plot.x_label) << "</text>\n";
  o << "<text transform=\"translate(16," << top + h / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
    << escape_markup(plot.y_label) << "</text>\n";
  double ly = top + 8;
  auto legend = [&](const std::string& color, const std::string& label, bool dashed, bool box) {
    const double lx = left + w + 14;
    if (box) {
      o << "<rect x=\"" << lx << "\" y=\"" << ly - 6 << "\" width=\"22\" height=\"10\" fill=\""
        << color << "\" fill-opacity=\"0.25\"/>\n";
    } else {
      o << "<line x1=\"" << lx << "\" x2=\"" << lx + 22 << "\" y1=\"" << ly << "\" y2=\"" << ly
        << "\" stroke=\"" << color << "\" stroke-width=\"2\""
        << (dashed ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
    }
    o << "<text x=\"" << lx + 28 << "\" y=\"" << ly + 4 << "\">" << escape_markup(label)
      << "</text>\n";
    ly += 18;
  };
  for (const auto& s : plot.series) legend(s.color, s.label, false, false);
  std::vector<std::string> seen;
  for (const auto& l : plot.levels) {
    if (std::find(seen.begin(), seen.end(), l.label) != seen.end()) continue;
    seen.push_back(l.label);
    legend(l.color, l.label, l.dashed, false);
  }
  for (const auto& s : plot.spans) {
    if (std::find(seen.begin(), seen.end(), s.label) != seen.end()) continue;
    seen.push_back(s.label);
    legend(s.color, s.label, false, true);
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace facectl
