#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/report/svg_plot.hpp"
#include "firmware-host/report/telemetry_csv.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

TEST(NiceTicks, UseOneTwoFiveStepsCoveringTheRange) {
  EXPECT_EQ(nice_ticks(0.0, 10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  const auto t = nice_ticks(-4.3, 18.2, 6);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);  // the first multiple of 5 at or above -4.3
  EXPECT_LE(t.back(), 18.2);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 5.0);
}

// Found by tests/fuzz/telemetry_csv_fuzz (a timeout): times of a few units
// at 1e16, where adding a step of 1 leaves a double unchanged, kept the tick
// loop from ever ending (a hang, growing without bound). Run in a child with
// an alarm, so that the old behaviour fails the test instead of hanging it.
TEST(NiceTicks, EndBelowTheResolutionOfDoubles) {
  EXPECT_EXIT(
      {
        alarm(10);
        const auto t = nice_ticks(1e16, 1e16 + 4, 10);
        std::exit(t.size() >= 1 && t.size() <= 11 ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(SvgPlot, DrawsSeriesLimitsAndLegend) {
  Plot p;
  p.title = "jaw <pitch>";
  p.series.push_back({"command", "#00f", {0, 1, 2}, {0, 10, 5}, 1.5});
  p.levels.push_back({"soft limit", "#f00", 18, true});
  const std::string svg = render_svg(p);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("jaw &lt;pitch&gt;"), std::string::npos);  // escaped
  EXPECT_NE(svg.find(">soft limit</text>"), std::string::npos);
}

TEST(TelemetryCsv, ATruncatedRowIsAnErrorNamingItsLine) {
  testing::TempFile f("tick,time_s,cmd.a\n0,0.000,1\n1,0.001\n", ".csv");
  try {
    read_telemetry_csv(f.path());
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              f.path() + ":3: expected 3 columns, found 2 (a truncated or foreign file?)");
  }
}

TEST(TelemetryCsv, ANonNumberIsAnErrorNamingLineAndColumn) {
  testing::TempFile f("tick,time_s,cmd.a\n0,0.000,1\n1,0.001,x\n", ".csv");
  const TelemetryTable t = read_telemetry_csv(f.path());
  try {
    t.numbers("cmd.a");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), f.path() + ":3: column 'cmd.a': expected a number, found 'x'");
  }
}

}  // namespace
}  // namespace facectl
