#include "firmware-host/cli/plot_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/report/telemetry_csv.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

// A model with one rotary actuator, jaw: all write_actuator_plots reads.
ControllerModel jaw_only() {
  ControllerModel m;
  ActuatorModel a;
  a.name = "jaw";
  m.actuators.push_back(a);
  return m;
}

// Found by tests/fuzz/telemetry_csv_fuzz under UBSan: a lim. cell beyond
// LimitFlags' 16 bits (70000) was converted with static_cast, which is
// undefined for a double out of the type's range. It is now an error naming
// the line, the column and the cell.
TEST(PlotCommand, LimitFlagsOutsideTheirBitsAreAnErrorNamingTheCell) {
  const ControllerModel m = jaw_only();
  testing::TempFile f("tick,time_s,cmd.jaw,fb.jaw,lim.jaw\n0,0.000,0,0,0\n1,0.001,0,0,70000\n",
                      ".csv");
  const TelemetryTable t = read_telemetry_csv(f.path());
  const std::string out = f.path() + ".plots";
  try {
    write_actuator_plots(m, t, {}, out);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              f.path() +
                  ":3: column 'lim.jaw': expected limit flag bits (an integer 0..65535), "
                  "found '70000'");
  }
  std::filesystem::remove_all(out);
}

TEST(PlotCommand, GoodLimitFlagsArePlotted) {
  const ControllerModel m = jaw_only();
  testing::TempFile f("tick,time_s,cmd.jaw,fb.jaw,lim.jaw\n0,0.000,0,0,0\n1,0.001,0,0,17\n",
                      ".csv");
  const std::string out = f.path() + ".plots";
  EXPECT_EQ(write_actuator_plots(m, read_telemetry_csv(f.path()), {}, out), 1);
  EXPECT_TRUE(std::filesystem::exists(out + "/jaw.svg"));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace facectl
