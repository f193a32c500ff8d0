#pragma once

#include <string>
#include <vector>

namespace facectl {

// A time-series chart rendered as a self-contained SVG file: lines, horizontal
// limit lines and shaded spans (e.g. states). Used for plots of actuator
// motion against its limits.
struct Plot {
  struct Series {
    std::string label;
    std::string color;
    std::vector<double> x;
    std::vector<double> y;
    double width = 1.5;
  };
  struct Level {  // a horizontal line across the chart
    std::string label;
    std::string color;
    double y = 0.0;
    bool dashed = false;
  };
  struct Span {  // a shaded vertical band over [x0, x1]
    std::string label;
    std::string color;
    double x0 = 0.0;
    double x1 = 0.0;
  };
  struct Mark {  // a short tick under the axis at x (e.g. a limit engaged)
    std::string color;
    double x = 0.0;
    int row = 0;
  };

  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<Series> series;
  std::vector<Level> levels;
  std::vector<Span> spans;
  std::vector<Mark> marks;
  std::vector<std::string> mark_rows;  // legend of the rows of marks
};

// Limit lines use colours nothing else in a plot uses, so that a screenshot of
// a report can be checked for them (tests/simulate).
inline constexpr const char* kHardLimitColor = "#ff00ff";
inline constexpr const char* kSoftLimitColor = "#a100c4";

// Series are drawn with at most four points per pixel column (first, min, max,
// last), so that a long series makes a small file and keeps its peaks.
std::string render_svg(const Plot& plot, int width = 960, int height = 340);

// "Nice" axis ticks (1, 2, 5 times a power of ten) covering [lo, hi].
std::vector<double> nice_ticks(double lo, double hi, int target_count = 6);

}  // namespace facectl
