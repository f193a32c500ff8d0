// The HTML report renders in a browser: headless Chromium takes a screenshot
// of index.html, which must show content and the plots' limit lines (drawn in
// kHardLimitColor, a colour nothing else on the page uses).
#include <gtest/gtest.h>

#include "facectl/face/image.hpp"
#include "firmware-host/report/svg_plot.hpp"
#include "simulate_process.hpp"

namespace facectl {
namespace {

struct Rgb {
  int r, g, b;
};

Rgb parse_color(const std::string& hex) {
  const auto v = std::stoi(hex.substr(1), nullptr, 16);
  return {(v >> 16) & 255, (v >> 8) & 255, v & 255};
}

// Pixels within `tolerance` of `c` in every channel.
long count_near(const face::Image& img, Rgb c, int tolerance) {
  long n = 0;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    if (std::abs(img.rgb[i] - c.r) <= tolerance && std::abs(img.rgb[i + 1] - c.g) <= tolerance &&
        std::abs(img.rgb[i + 2] - c.b) <= tolerance) {
      ++n;
    }
  }
  return n;
}

TEST(SimulateHtml, RendersInHeadlessChromiumWithTheLimitLines) {
  ASSERT_EQ(std::system("command -v chromium > /dev/null"), 0)
      << "chromium is not installed (scripts/setup.sh installs it)";
  testing::TempDir tmp;
  const auto r = testing::run_facectl(
      {"simulate", "--rig", testing::source_path("config/rigs/default.yaml"), "--show",
       testing::source_path("config/shows/demo.yaml"), "--out", tmp / "out", "--duration", "3"},
      tmp / "log");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string png = tmp / "page.png";
  const std::string cmd =
      "chromium --headless --no-sandbox --disable-gpu --hide-scrollbars "
      "--user-data-dir='" +
      (tmp / "profile") + "' --screenshot='" + png + "' --window-size=1200,1600 'file://" +
      (tmp / "out/index.html") + "' > '" + (tmp / "chromium.log") + "' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << testing::read_text(tmp.path() / "chromium.log");
  const face::Image img = face::read_png(png);
  ASSERT_EQ(img.width, 1200);
  ASSERT_EQ(img.height, 1600);
  const long pixels = static_cast<long>(img.width) * img.height;
  const long white = count_near(img, {255, 255, 255}, 8);
  EXPECT_LT(white, pixels * 98 / 100) << "the page is blank";
  const long limit = count_near(img, parse_color(kHardLimitColor), 40);
  EXPECT_GT(limit, 200) << "no hard-limit lines on the page: the plots did not render";
}

}  // namespace
}  // namespace facectl
