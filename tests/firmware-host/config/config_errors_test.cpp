// Every bad configuration gets an error naming file:line:column, the key,
// what was expected and what was found.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "firmware-host/config/expression_library.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "firmware-host/model/model_builder.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

using testing::TempFile;

const HeadConfig& head() {
  static const HeadConfig h =
      load_head_config(std::string(FACECTL_SOURCE_DIR) + "/config/heads/default/head.yaml");
  return h;
}

// A one-actuator rig with `actuator_extra` lines spliced into the actuator.
std::string rig(const std::string& actuator_lines) {
  return "rig:\n"
         "  name: t\n"
         "  buses:\n"
         "    - { name: can0, type: can, interface: can0, bitrate: 1000000 }\n"
         "  actuators:\n"
         "    - name: jaw\n"
         "      kind: rotary\n"
         "      bus: can0\n"
         "      address: 1\n" +
         actuator_lines;
}

const std::string kGoodActuator =
    "      position_deg: { min: -6, max: 20 }\n"
    "      max_velocity_deg_s: 100\n"
    "      max_acceleration_deg_s2: 1000\n"
    "      rest_deg: 0\n"
    "      map: { terms: { jaw_pitch_deg: 1 } }\n";

// The error for a rig text, with the temp path replaced by RIG.
std::string rig_error(const std::string& text) {
  TempFile f(text);
  try {
    const RigConfig r = load_rig_config(f.path(), head().layout);
    RuntimeConfig rt;
    const BuiltModel b = build_model(head(), r, rt);
    if (!b.problems.empty()) throw ConfigError(b.problems.front());
  } catch (const ConfigError& e) {
    std::string msg = e.what();
    const auto at = msg.find(f.path());
    if (at != std::string::npos) msg.replace(at, f.path().size(), "RIG");
    return msg;
  }
  return "no error";
}

// The ConfigError that `load` throws.
std::string load_error(const std::function<void()>& load) {
  try {
    load();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ConfigErrors, AGoodRigLoads) {
  EXPECT_EQ(rig_error(rig(kGoodActuator)), "no error");
}

TEST(ConfigErrors, YamlSyntaxErrorsNameTheirPosition) {
  EXPECT_EQ(rig_error("rig:\n  name: [unclosed\n"),
            "RIG:3:1: YAML syntax error: end of sequence flow not found");
}

TEST(ConfigErrors, AMissingFileIsNamed) {
  try {
    load_rig_config("/nonexistent/rig.yaml", head().layout);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "/nonexistent/rig.yaml: cannot open file (No such file or directory; expected a "
                 "readable YAML file)");
  }
}

TEST(ConfigErrors, ANegativeVelocityNamesKeyExpectedAndFound) {
  std::string a = kGoodActuator;
  a.replace(a.find("100"), 3, "-3");
  EXPECT_EQ(rig_error(rig(a)),
            "RIG:11:27: rig.actuators[0].max_velocity_deg_s: expected a number > 0, found '-3'");
}

TEST(ConfigErrors, ATypoIsAnUnknownKeyNotASilentDefault) {
  std::string a = kGoodActuator;
  a.replace(a.find("max_velocity"), 12, "max_velocty");
  const std::string e = rig_error(rig(a));
  EXPECT_NE(e.find("RIG:11:7: rig.actuators[0].max_velocty_deg_s: expected one of:"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("found unknown key 'max_velocty_deg_s'"), std::string::npos) << e;
}

// Found by tests/fuzz (head_config_fuzz, expressions_fuzz): a sequence or a
// mapping as a key escaped as yaml-cpp's "bad conversion", naming no file.
TEST(ConfigErrors, ASequenceAsAKeyNamesWhereItIs) {
  std::string a = kGoodActuator;
  a.replace(a.find("max: 20 }"), 9, "max: 20, [6, 7] }");
  EXPECT_EQ(rig_error(rig(a)),
            "RIG:10:41: rig.actuators[0].position_deg: expected a plain name as mapping key, found "
            "a sequence");
}

TEST(ConfigErrors, AMappingAsAKeyNamesWhereItIs) {
  TempFile f("expressions:\n  neutral: {}\n  ? { pitch_deg: 1 }\n  : {}\n");
  try {
    ExpressionLibrary::load(f.path(), head().layout);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        f.path() + ":3:5: expressions: expected a plain name as mapping key, found a mapping");
  }
}

// Issue 21: yaml-cpp keeps both copies of a repeated key. Lookups took the
// first (a second soft_position_deg was ignored, `rate_hz: 1000` then
// `rate_hz: 5` ran at 1000 Hz), iteration the last (a repeated term won).
TEST(ConfigErrors, ARepeatedKeyNamesBothLines) {
  EXPECT_EQ(rig_error(rig(kGoodActuator + "      soft_position_deg: { min: -5, max: 19 }\n" +
                          "      soft_position_deg: { min: -1, max: 1 }\n")),
            "RIG:16:7: duplicate key 'rig.actuators[0].soft_position_deg' (first at line 15)");
  std::string a = kGoodActuator;
  a.replace(a.find("jaw_pitch_deg: 1 }"), 18, "jaw_pitch_deg: 1, jaw_pitch_deg: 50 }");
  EXPECT_EQ(rig_error(rig(a)),
            "RIG:14:41: duplicate key 'rig.actuators[0].map.terms.jaw_pitch_deg' (first at line "
            "14)");
  TempFile f("runtime:\n  rate_hz: 1000\n  rate_hz: 5\nhead: h\nrig: r\nexpressions: e\n");
  EXPECT_EQ(load_error([&] { load_runtime_config(f.path()); }),
            f.path() + ":3:3: duplicate key 'runtime.rate_hz' (first at line 2)");
}

// Issue 21: a directory as a file gave "basic_filebuf::underflow", naming no
// file; an empty file named no line.
TEST(ConfigErrors, ADirectoryOrAnEmptyFileIsNamed) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  EXPECT_EQ(load_error([&] { load_runtime_config(dir); }),
            dir + ": is a directory, expected a YAML file");
  EXPECT_EQ(load_error([&] { load_rig_config(dir, head().layout); }),
            dir + ": is a directory, expected a YAML file");
  TempFile f("");
  EXPECT_EQ(load_error([&] { load_runtime_config(f.path()); }),
            f.path() + ":1:1: expected a YAML mapping at the top level, found nothing");
}

TEST(ConfigErrors, UnitsMustMatchTheActuatorKind) {
  std::string a = kGoodActuator;
  a.replace(a.find("rest_deg"), 8, "rest_mm");
  const std::string e = rig_error(rig(a));
  EXPECT_NE(e.find("found unknown key 'rest_mm'"), std::string::npos) << e;
}

TEST(ConfigErrors, ASoftRangeOutsideTheHardwareRangeIsRefused) {
  const std::string e =
      rig_error(rig(kGoodActuator + "      soft_position_deg: { min: -8, max: 18 }\n"));
  EXPECT_EQ(e,
            "RIG:15:26: rig.actuators[0].soft_position_deg: expected a soft range inside "
            "position_deg [-6.000000, 20.000000], found [-8.000000, 18.000000]");
}

TEST(ConfigErrors, AnUnknownBusOrSignalIsNamed) {
  std::string a = kGoodActuator;
  EXPECT_EQ(rig_error(rig(a).replace(rig(a).find("bus: can0"), 9, "bus: can9")),
            "RIG:8:12: rig.actuators[0].bus: expected the name of a bus of this rig, found 'can9'");
  a.replace(a.find("jaw_pitch_deg"), 13, "jaw_pitch");
  const std::string e = rig_error(rig(a));
  EXPECT_NE(e.find("RIG:14:34: rig.actuators[0].map.terms.jaw_pitch: expected a face signal"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("found unknown signal 'jaw_pitch'"), std::string::npos) << e;
}

TEST(ConfigErrors, NonFiniteNumbersAreRefused) {
  std::string a = kGoodActuator;
  a.replace(a.find("1000"), 4, ".nan");
  EXPECT_EQ(rig_error(rig(a)),
            "RIG:12:32: rig.actuators[0].max_acceleration_deg_s2: expected a finite number, found "
            "'.nan'");
}

TEST(ConfigErrors, AnActuatorThatNothingDrivesIsRefused) {
  std::string a = kGoodActuator;
  a.replace(a.find("jaw_pitch_deg: 1"), 16, "jaw_pitch_deg: 0");
  const std::string e = rig_error(rig(a));
  EXPECT_NE(e.find("RIG:14:12: actuator 'jaw': nothing drives it (no non-zero term or point"),
            std::string::npos)
      << e;
}

TEST(ConfigErrors, TwoActuatorsOnOneAddressAreRefused) {
  std::string text = rig(kGoodActuator);
  text +=
      "    - name: jaw2\n      kind: rotary\n      bus: can0\n      address: 1\n" + kGoodActuator;
  EXPECT_EQ(rig_error(text),
            "RIG:18:16: rig.actuators[1].address: expected an address not used by another "
            "actuator on bus can0, found '1'");
}

TEST(ConfigErrors, AMappingThatCanOverflowIsRefused) {
  std::string a = kGoodActuator;
  a.replace(a.find("jaw_pitch_deg: 1"), 16, "jaw_pitch_deg: 1e306, jaw_yaw_deg: -1e306");
  const std::string e = rig_error(rig(a));
  EXPECT_NE(e.find("'jaw'.map: expected gains and offset that keep the command finite"),
            std::string::npos)
      << e;
}

TEST(ConfigErrors, APlantLatencyLongerThanItsDelayLineIsRefused) {
  TempFile f(rig(kGoodActuator + "      plant: { latency_ms: 40 }\n"));
  const RigConfig r = load_rig_config(f.path(), head().layout);
  RuntimeConfig rt;
  rt.rate_hz = 2000;  // 40 ms is 80 ticks at 2 kHz
  try {
    build_model(head(), r, rt);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              f.path() +
                  ":15:14: rig.actuators 'jaw'.plant.latency_ms: expected less than 60 "
                  "ticks of latency at 2000.000000 Hz, found 40.000000 ms");
  }
}

TEST(ConfigErrors, PlantKeysAreCheckedAgainstTheirModel) {
  const auto plant = [](const std::string& block) {
    return rig_error(rig(kGoodActuator + "      plant: " + block + "\n"));
  };
  EXPECT_EQ(plant("{ model: pd, natural_frequency_hz: 12, deadband_deg: 0.1 }"), "no error");
  std::string e = plant("{ model: second }");
  EXPECT_NE(e.find("RIG:15:23: rig.actuators[0].plant.model: expected first_order or pd"),
            std::string::npos)
      << e;
  e = plant("{ model: pd, time_constant_ms: 20 }");
  EXPECT_NE(e.find("RIG:15:45: rig.actuators[0].plant.time_constant_ms: expected no "
                   "time_constant_ms with model: pd"),
            std::string::npos)
      << e;
  e = plant("{ damping_ratio: 0.5 }");
  EXPECT_NE(e.find("plant.damping_ratio: expected no damping_ratio without model: pd"),
            std::string::npos)
      << e;
  // Play beyond a tenth of travel (26 deg here) is a typo, not a servo.
  e = plant("{ backlash_deg: 5 }");
  EXPECT_NE(e.find("RIG:15:30: rig.actuators[0].plant.backlash_deg: expected a number in [0, 2.6], "
                   "found '5'"),
            std::string::npos)
      << e;
}

TEST(ConfigErrors, RuntimeSettingsAreCheckedAgainstEachOther) {
  TempFile f(
      "runtime: { input_timeout_ms: 20, show_rate_hz: 50 }\nhead: h\nrig: r\nexpressions: e\n");
  try {
    load_runtime_config(f.path());
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), f.path() +
                                         ":1:48: runtime.show_rate_hz: expected show_rate_hz "
                                         "of at least 100.000000 Hz (two commands per "
                                         "input_timeout_ms), found '50'");
  }
  TempFile g("runtime: { realtime: { priority: 80.5 } }\nhead: h\nrig: r\nexpressions: e\n");
  try {
    load_runtime_config(g.path());
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(
        std::string(e.what()).find("runtime.realtime.priority: expected an integer, found '80.5'"),
        std::string::npos)
        << e.what();
  }
}

TEST(ConfigErrors, DuplicateMusclesInAHeadAreRefused) {
  TempFile f("head:\n  name: h\n  muscles: [a_l, b_l, a_l]\n");
  try {
    load_head_config(f.path());
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), f.path() +
                                         ":3:23: head.muscles[2]: expected a unique muscle "
                                         "name, found duplicate 'a_l'");
  }
}

TEST(ConfigErrors, AnActuatorCoupledLimitOverAMandibleStrutIsRefused) {
  // Struts follow the jaw's pose, not their own limiters: such a limit could
  // not be kept exactly, so the rig is refused, pointing to a face limit.
  std::ifstream in(std::string(FACECTL_SOURCE_DIR) + "/config/rigs/default.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string at = "  coupled_limits:\n";
  ASSERT_NE(text.find(at), std::string::npos);
  text.insert(text.find(at) + at.size(),
              "    - name: jaw_against_lower_lip\n"
              "      actuators: { lower_lip: 0.5, jaw_digastric: 1 }\n"
              "      max: 40\n");
  const auto term = static_cast<long>(text.find("jaw_digastric: 1 }"));
  const std::string line = std::to_string(std::count(text.begin(), text.begin() + term, '\n') + 1);
  const std::string msg = rig_error(text);
  EXPECT_EQ(msg.rfind("RIG:" + line + ":", 0), 0u) << msg;
  EXPECT_NE(msg.find("rig.coupled_limits[0].actuators.jaw_digastric: expected an actuator that is "
                     "not a strut of the mandible mechanism"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("face coupled limit over jaw_pitch_deg"), std::string::npos) << msg;
  EXPECT_NE(msg.find("found strut 'jaw_digastric'"), std::string::npos) << msg;
}

// Issue 21: these named the file but not the line.
TEST(ConfigErrors, ACoupledLimitTheNeutralPoseBreaksNamesItsLine) {
  const std::string text = rig(kGoodActuator) +
                           "  coupled_limits:\n"
                           "    - name: open\n"
                           "      face: { jaw_pitch_deg: 1 }\n"
                           "      max: -1\n";
  EXPECT_EQ(rig_error(text),
            "RIG:16:7: rig.coupled_limits: expected a limit that the head's neutral pose "
            "satisfies, found 'open' = 0.000000 at the neutral pose, above its max -1.000000");
}

TEST(ConfigErrors, AnActuatorCoupledLimitTheRestPoseBreaksNamesItsLine) {
  const std::string text = rig(kGoodActuator) +
                           "  coupled_limits:\n"
                           "    - name: low\n"
                           "      actuators: { jaw: 1 }\n"
                           "      max: -1\n";
  EXPECT_EQ(rig_error(text),
            "RIG:16:7: rig.coupled_limits: expected a limit that every actuator's rest position "
            "satisfies, found 'low' = 0.000000 at rest, above its max -1.000000");
}

TEST(ConfigErrors, ANeutralPoseOutsideTheEnvelopeNamesItsLine) {
  std::ifstream in(std::string(FACECTL_SOURCE_DIR) + "/config/heads/default/head.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string at = "  neutral: {}\n";
  ASSERT_NE(text.find(at), std::string::npos);
  text.replace(text.find(at), at.size(), "  neutral:\n    mandible: { pitch_deg: 25 }\n");
  // A copy of the whole head, so that its face model resolves beside it.
  testing::TempDir tmp;
  std::filesystem::copy(std::string(FACECTL_SOURCE_DIR) + "/config/heads/default", tmp.path(),
                        std::filesystem::copy_options::recursive);
  const std::string copy = tmp.file("head.yaml");
  std::ofstream(copy, std::ios::trunc) << text;
  RigConfig r;
  std::string msg = load_error([&] {
    const HeadConfig h = load_head_config(copy);
    r = load_rig_config(std::string(FACECTL_SOURCE_DIR) + "/config/rigs/default.yaml", h.layout);
    RuntimeConfig rt;
    (void)build_model(h, r, rt);
  });
  EXPECT_EQ(msg.rfind(copy + ":69:5: head.neutral: expected a pose inside the envelope", 0), 0u)
      << msg;
}

TEST(ConfigErrors, TheShippedConfigurationLoads) {
  const LoadedConfig cfg = load_config(default_config_path());
  EXPECT_EQ(cfg.built.model.actuators.size(), 26u);
  EXPECT_EQ(cfg.built.model.buses.size(), 2u);
  EXPECT_FALSE(cfg.built.model.envelope_widened);
  EXPECT_TRUE(cfg.show.has_value());
}

}  // namespace
}  // namespace facectl
