// facectl verify: passes the shipped rigs, fails each deliberately broken rig
// (a shipped rig with one edit, or one under tests/firmware-host/verify/rigs)
// naming the actuator, the limit and a witness, and its static proof is sound
// (sampling never finds a command outside it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <tuple>

#include "control/analysis/channel_bound.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/verify/static_proof.hpp"
#include "firmware-host/verify/verify_command.hpp"
#include "tests/support/edited_rig.hpp"
#include "tests/support/sample_count.hpp"
#include "tests/support/temp_file.hpp"
#include "tests/support/text_files.hpp"

namespace facectl {
namespace {

const std::string kSource = FACECTL_SOURCE_DIR;
using testing::EditedRig;

EditedRig hobby() {
  return EditedRig("config/rigs/hobby.yaml");
}
// The hobby rig with linear terms only (no point channels): exact LP ends and witnesses.
EditedRig hobby_terms() {
  return EditedRig("tests/data/rigs/hobby_terms.yaml");
}
EditedRig default_rig() {
  return EditedRig("config/rigs/default.yaml");
}

LoadedConfig load_rig(const std::string& rig) {
  ConfigOverrides o;
  o.rig_path = rig;
  o.keep_problems = true;
  return load_config(default_config_path(), o);
}

const verify::Finding* find_failure(const std::vector<verify::Finding>& findings,
                                    const std::string& check) {
  for (const auto& f : findings) {
    if (f.severity == verify::Finding::Severity::kFail && f.check == check) return &f;
  }
  return nullptr;
}

// One `facectl verify` run: its exit code, its JSON report and what it printed.
struct VerifyRun {
  int code = -1;
  nlohmann::json report;
  std::string out;
};

VerifyRun run_verify(const std::string& rig, std::vector<std::string> shows, std::uint64_t ticks) {
  const testing::TempFile json("", ".json");
  VerifyOptions o;
  o.rig = rig;
  o.shows = std::move(shows);
  o.ticks = ticks;
  o.json = json.path();
  VerifyRun r;
  ::testing::internal::CaptureStdout();
  r.code = verify_command(o);
  r.out = ::testing::internal::GetCapturedStdout();
  std::ifstream in(json.path());
  if (in.peek() != std::ifstream::traits_type::eof()) in >> r.report;
  return r;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The FAIL findings of one section of the JSON report ("static", "adversarial").
std::vector<nlohmann::json> failures(const VerifyRun& r, const std::string& section,
                                     const std::string& check) {
  std::vector<nlohmann::json> out;
  if (!r.report.contains(section)) return out;
  for (const auto& f : r.report[section]["findings"]) {
    if (f["severity"] == "FAIL" && f["check"] == check) out.push_back(f);
  }
  return out;
}

TEST(Verify, PassesBothShippedRigs) {
  VerifyOptions o;
  o.ticks = static_cast<std::uint64_t>(testing::sample_count(100'000));
  o.rig = kSource + "/config/rigs/default.yaml";
  o.shows = {kSource + "/config/shows/demo.yaml"};
  EXPECT_EQ(verify_command(o), 0);
  o.shows.clear();
  for (const char* hobby_rig :
       {"hobby", "hobby_pca9685", "hobby_maestro", "hobby_dynamixel", "hobby_feetech"}) {
    o.rig = kSource + "/config/rigs/" + hobby_rig + ".yaml";
    EXPECT_EQ(verify_command(o), 0) << hobby_rig;
  }
  o.rig = kSource + "/tests/data/rigs/hobby_terms.yaml";  // the fixture of the tests below
  EXPECT_EQ(verify_command(o), 0);
}

TEST(Verify, ARigWithActuatorCoupledLimitsPassesItsAdversarialSearch) {
  // Four actuator coupled limits that the mapping's extremes overrun, over
  // jerk-limited and shared actuators: a million adversarial ticks (a tenth
  // when sanitized) find no violation of them, nor of any actuator's own
  // limits (docs/SAFETY.md).
  VerifyOptions o;
  o.rig = kSource + "/tests/firmware-host/verify/rigs/actuator_coupled.yaml";
  o.ticks = static_cast<std::uint64_t>(testing::sample_count(1'000'000));
  EXPECT_EQ(verify_command(o), 0);
}

TEST(Verify, AMappingBeyondAHardwareLimitFailsWithItsWitness) {
  // mouth_corner_l's mapping reaches 60 deg, beyond its 50 deg hardware limit.
  const auto rig = hobby_terms()
                       .replace(
                           "terms: { zygomaticus_major_l: 35, levator_anguli_oris_l: 5, "
                           "depressor_anguli_oris_l: -40 }",
                           "terms: { zygomaticus_major_l: 55, levator_anguli_oris_l: 5, "
                           "depressor_anguli_oris_l: -40 }")
                       .write();
  const auto cfg = load_rig(rig.path());
  const auto proof = verify::prove(cfg);
  const auto* f = find_failure(proof.findings, "hardware range");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->subject, "mouth_corner_l");
  EXPECT_NE(f->message.find("60 deg > hardware max 50 deg"), std::string::npos) << f->message;
  EXPECT_EQ(f->witness, "zygomaticus_major_l=1, levator_anguli_oris_l=1");
  VerifyOptions o;
  o.rig = rig.path();
  o.ticks = 1000;
  EXPECT_EQ(verify_command(o), 1);
}

TEST(Verify, ANonMonotoneCalibrationFailsNamingThePoints) {
  // brow_l's calibration turns back: 30 deg at 4 mm, 25 deg at 8 mm.
  const auto rig = hobby_terms()
                       .replace(
                           "corrugator_supercilii_l: -3 }   # mm of lift\n"
                           "        calibration: { effector_mm: [-3, 0, 4, 8, 10], "
                           "position_deg: [0, 5, 30, 60, 72] }",
                           "corrugator_supercilii_l: -3 }\n"
                           "        calibration: { effector_mm: [-3, 0, 4, 8, 10], "
                           "position_deg: [0, 5, 30, 25, 72] }")
                       .write();
  const auto cfg = load_rig(rig.path());
  const auto proof = verify::prove(cfg);
  const auto* f = find_failure(proof.findings, "rig");
  ASSERT_NE(f, nullptr);
  EXPECT_NE(f->message.find("calibration is not monotone: effector_mm '4' -> position_deg '30', "
                            "but effector_mm '8' -> position_deg '25' (actuator 'brow_l')"),
            std::string::npos)
      << f->message;
  // And `facectl run` refuses such a rig outright.
  ConfigOverrides strict;
  strict.rig_path = rig.path();
  EXPECT_THROW(load_config(default_config_path(), strict), ConfigError);
}

TEST(Verify, AnEnvelopeWidenedWithoutTheOverrideIsRefused) {
  const auto rig =
      hobby().replace("pitch_deg: { min: 0, max: 15 }", "pitch_deg: { min: 0, max: 25 }").write();
  VerifyOptions o;
  o.rig = rig.path();
  o.ticks = 1000;
  EXPECT_EQ(verify_command(o), 2);  // the rig is refused as it is read
  try {
    load_rig(o.rig);
    FAIL() << "a widened envelope was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(rig.path() +
                                         ":14:16: rig.mandible_envelope."
                                         "pitch_deg: expected a range inside the design envelope "
                                         "-4..18 deg (widening needs `widen_override: true`), "
                                         "found [0.000000, 25.000000]"),
              std::string::npos)
        << e.what();
  }
}

TEST(Verify, AntagonistsAllowedToCoActivateFail) {
  // No coupled limit keeps the lip-corner antagonists apart.
  const auto rig = hobby()
                       .replace(
                           "  coupled_limits:\n"
                           "    - name: antagonists_lip_corner_l\n"
                           "      face: { zygomaticus_major_l: 1, depressor_anguli_oris_l: 1 }\n"
                           "      max: 1.0\n"
                           "    - name: antagonists_lip_corner_r\n"
                           "      face: { zygomaticus_major_r: 1, depressor_anguli_oris_r: 1 }\n"
                           "      max: 1.0\n",
                           "")
                       .write();
  const auto cfg = load_rig(rig.path());
  const auto proof = verify::prove(cfg);
  const auto* f = find_failure(proof.findings, "antagonists");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->subject, "zygomaticus_major_l + depressor_anguli_oris_l");
  EXPECT_NE(f->message.find("co-activation reaches 2 > max_sum 1"), std::string::npos);
  EXPECT_EQ(f->witness, "zygomaticus_major_l=1, depressor_anguli_oris_l=1");
}

TEST(Verify, AnActuatorThatNothingDrivesFails) {
  const auto rig =
      hobby().replace("terms: { neck_pan_deg: 1.0 }", "terms: { neck_pan_deg: 0 }").write();
  const auto cfg = load_rig(rig.path());
  const auto proof = verify::prove(cfg);
  const auto* f = find_failure(proof.findings, "rig");
  ASSERT_NE(f, nullptr);
  EXPECT_NE(f->message.find("actuator 'neck_pan': nothing drives it"), std::string::npos);
}

TEST(Verify, AnOvercommittedBusFailsWithItsNumbers) {
  const auto cfg = load_rig(kSource + "/tests/firmware-host/verify/rigs/bus_overcommitted.yaml");
  const auto proof = verify::prove(cfg);
  const auto* f = find_failure(proof.findings, "bus budget");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->subject, "can0");
  EXPECT_NE(f->message.find("216.0% of 125000 bit/s"), std::string::npos) << f->message;
  // `facectl run` refuses it as it loads.
  ConfigOverrides strict;
  strict.rig_path = kSource + "/tests/firmware-host/verify/rigs/bus_overcommitted.yaml";
  EXPECT_THROW(load_config(default_config_path(), strict), ConfigError);
}

// Issue 19, item 4: a show that holds the neck at an end of travel trips the
// servo's overload protection; every tick after it is FAULT. The show check
// fails, naming the first such tick's time and the transition's reason, once.
TEST(Verify, AShowThatFaultsTheHeadFailsWithItsTimeAndReason) {
  const VerifyRun r =
      run_verify(kSource + "/config/rigs/default.yaml",
                 {kSource + "/tests/firmware-host/verify/shows/neck_held_at_extreme.yaml"}, 1000);
  EXPECT_EQ(r.code, 1);
  ASSERT_TRUE(r.report.contains("shows")) << r.out;
  ASSERT_EQ(r.report["shows"].size(), 1u) << r.out;
  const auto& show = r.report["shows"][0];
  EXPECT_FALSE(show.value("passed", true));
  ASSERT_TRUE(show.contains("fault")) << show.dump(2);
  const auto& fault = show["fault"];
  EXPECT_EQ(fault["state"], "FAULT");
  // 2 s to get there, then the 20 s budget of continuous time at the extreme.
  EXPECT_GT(fault["at_s"].get<double>(), 20.0);
  EXPECT_LT(fault["at_s"].get<double>(), 24.0);
  EXPECT_NE(fault["reason"].get<std::string>().find(
                "bus fault — thermal: neck_pan held at an end of travel longer than its 20 s "
                "budget"),
            std::string::npos)
      << fault["reason"];
  EXPECT_GT(fault["ticks"].get<std::uint64_t>(), 6000u);  // the rest of the show, and settling
  // Said once, not once per tick.
  EXPECT_EQ(count(r.out, "neck_pan held at an end of travel"), 1u) << r.out;
}

// Issue 19, item 5: a rig limit above what the actuator's servo can do fails,
// naming the actuator, the quantity and both values with their units.
TEST(Verify, ARigLimitBeyondItsServoFailsNamingBothValues) {
  // brow_l's rig limit is max_acceleration_deg_s2: 4000, ten times its servo's.
  const auto rig = hobby()
                       .replace("backlash_deg: 0.5 }\n      expect_direction: { frontalis_l: +1 }",
                                "backlash_deg: 0.5,\n"
                                "               max_acceleration_deg_s2: 400 }\n"
                                "      expect_direction: { frontalis_l: +1 }")
                       .write();
  const VerifyRun r = run_verify(rig.path(), {}, 1000);
  EXPECT_EQ(r.code, 1);
  const auto found = failures(r, "static", "capability");
  ASSERT_EQ(found.size(), 1u) << r.out;
  EXPECT_EQ(found[0]["subject"], "brow_l");
  EXPECT_NE(found[0]["message"].get<std::string>().find(
                "max_acceleration_deg_s2 4000 deg/s^2 > the servo's 400 deg/s^2"),
            std::string::npos)
      << found[0]["message"];
  // Every shipped rig's servos can do what its limits ask.
  int shipped = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSource + "/config/rigs")) {
    if (entry.path().extension() != ".yaml") continue;
    ++shipped;
    const auto proof = verify::prove(load_rig(entry.path().string()));
    const auto* f = find_failure(proof.findings, "capability");
    EXPECT_EQ(f, nullptr) << entry.path() << ": " << f->subject << ": " << f->message;
  }
  EXPECT_GE(shipped, 6);  // default, hobby, hobby_dynamixel, hobby_feetech, hobby_maestro,
                          // hobby_pca9685
}

// hobby_pca9685.yaml copies hobby.yaml's head (the schema has no include):
// only the bus may differ.
TEST(Verify, HobbyPca9685IsTheHobbyHeadOnAPca9685) {
  const auto from_envelope = [](const std::string& text) {
    return text.substr(text.find("  # Hobby jaws rarely yaw"));
  };
  const std::string modbus = testing::read_text(kSource + "/config/rigs/hobby.yaml");
  const std::string pca = testing::read_text(kSource + "/config/rigs/hobby_pca9685.yaml");
  EXPECT_EQ(from_envelope(pca), from_envelope(modbus));
  EXPECT_NE(pca.find("type: pca9685"), std::string::npos);
  const std::string maestro = testing::read_text(kSource + "/config/rigs/hobby_maestro.yaml");
  EXPECT_EQ(from_envelope(maestro), from_envelope(modbus));
  EXPECT_NE(maestro.find("type: maestro"), std::string::npos);
}

// hobby_feetech.yaml copies hobby_dynamixel.yaml's head: only the bus and
// the servos' protection (their own limits) may differ.
TEST(Verify, HobbyFeetechIsTheHobbyHeadOnFeetechServos) {
  const auto from_envelope = [](const std::string& text) {
    std::istringstream in(text.substr(text.find("  # Hobby jaws rarely yaw")));
    std::string out, line;
    bool in_block = false;
    while (std::getline(in, line)) {
      const bool comment = line.rfind("      # Drive-level protection", 0) == 0;
      const bool block = line.rfind("      protection: &", 0) == 0;
      if (comment || block) in_block = true;
      const bool inside = line.rfind("      #", 0) == 0 || line.rfind("        ", 0) == 0;
      if (in_block && (comment || block || inside)) continue;
      in_block = false;
      if (line.rfind("      protection: *", 0) == 0) continue;
      out += line + "\n";
    }
    return out;
  };
  const std::string dxl = testing::read_text(kSource + "/config/rigs/hobby_dynamixel.yaml");
  const std::string ft = testing::read_text(kSource + "/config/rigs/hobby_feetech.yaml");
  EXPECT_EQ(from_envelope(ft), from_envelope(dxl));
  EXPECT_NE(ft.find("type: feetech"), std::string::npos);
}

// A neck servo slower than the rig's limit cannot follow: the static check
// names it, and every adversarial finding says whom it is about.
TEST(Verify, AServoSlowerThanItsLimitIsNamed) {
  // neck_pan's rig limit is max_velocity_deg_s: 120, twice its servo's.
  const auto rig =
      default_rig()
          .replace("backlash_deg: 0.05 }\n      expect_direction: { neck_pan_deg: +1 }",
                   "backlash_deg: 0.05,\n"
                   "               max_velocity_deg_s: 60 }\n"
                   "      expect_direction: { neck_pan_deg: +1 }")
          .write();
  const VerifyRun r = run_verify(rig.path(), {}, 20'000);
  EXPECT_EQ(r.code, 1);
  const auto capability = failures(r, "static", "capability");
  ASSERT_EQ(capability.size(), 1u) << r.out;
  EXPECT_EQ(capability[0]["subject"], "neck_pan");
  EXPECT_NE(capability[0]["message"].get<std::string>().find(
                "max_velocity_deg_s 120 deg/s > the servo's 60 deg/s"),
            std::string::npos)
      << capability[0]["message"];
  ASSERT_TRUE(r.report.contains("adversarial")) << r.out;
  for (const auto& f : r.report["adversarial"]["findings"]) {
    EXPECT_NE(f["subject"], "") << f.dump();
  }
}

// A cause that faults the head again after every re-enable is one finding,
// not one per fault: it names the actuator, the reason, the count, the first
// time and what was measured then. Here a brow's servo rings (PD, damping
// 0.1) past a hardware range no wider than its soft range, narrowed to ±35.5° so
// the brow's commands (up to about 30°) come within reach of the ringing.
TEST(Verify, TheSearchGroupsRepeatedFaultsByCause) {
  const auto rig = default_rig()
                       .replace(
                           "position_deg: { min: -45, max: 45 }\n"
                           "      soft_position_deg: { min: -40, max: 40 }\n"
                           "      max_velocity_deg_s: 300\n"
                           "      max_acceleration_deg_s2: 4000\n"
                           "      rest_deg: 0\n"
                           "      plant: { time_constant_ms: 25, latency_ms: 2, noise_deg: 0.05, "
                           "deadband_deg: 0.15, backlash_deg: 0.5 }\n"
                           "      expect_direction: { frontalis_inner_l: +1",
                           "position_deg: { min: -35.5, max: 35.5 }\n"
                           "      soft_position_deg: { min: -35, max: 35 }\n"
                           "      max_velocity_deg_s: 300\n"
                           "      max_acceleration_deg_s2: 4000\n"
                           "      rest_deg: 0\n"
                           "      plant: { model: pd, natural_frequency_hz: 8, damping_ratio: 0.1, "
                           "latency_ms: 2 }\n"
                           "      expect_direction: { frontalis_inner_l: +1")
                       .write();
  const VerifyRun r = run_verify(rig.path(), {}, 20'000);
  EXPECT_EQ(r.code, 1) << r.out;
  const auto faults = failures(r, "adversarial", "fault");
  ASSERT_EQ(faults.size(), 1u) << r.out;
  EXPECT_EQ(faults[0]["subject"], "brow_inner_l");
  const std::string message = faults[0]["message"];
  const std::string head =
      "the controller entered FAULT (actuator measured outside its hardware range) ";
  ASSERT_EQ(message.rfind(head, 0), 0u) << message;
  const std::uint64_t times = std::stoull(message.substr(head.size()));
  EXPECT_GT(times, 1u) << message;
  EXPECT_EQ(times, r.report["adversarial"]["violations"].get<std::uint64_t>()) << message;
  EXPECT_NE(message.find(" time(s), first at t = "), std::string::npos) << message;
  EXPECT_NE(message.find("(brow_inner_l measured at "), std::string::npos) << message;
  EXPECT_NE(message.find(" deg, outside its hardware range -35.5..35.5 deg)"), std::string::npos)
      << message;
  // Faults are not limit violations: no "N limit violations in all" line.
  EXPECT_TRUE(failures(r, "adversarial", "adversarial").empty()) << r.out;
  EXPECT_EQ(count(r.out, "entered FAULT"), 1u) << r.out;
}

// A mapping wired the wrong way round on a symmetric range stays inside every
// range; the direction the rig expects for a named face signal catches it.
TEST(Verify, AFlippedMappingFailsItsExpectedDirection) {
  const auto rig =
      hobby().replace("terms: { neck_pan_deg: 1.0 }", "terms: { neck_pan_deg: -1.0 }").write();
  const VerifyRun r = run_verify(rig.path(), {}, 1000);
  EXPECT_EQ(r.code, 1) << r.out;
  const auto found = failures(r, "static", "direction");
  ASSERT_EQ(found.size(), 1u) << r.out;
  EXPECT_EQ(found[0]["subject"], "neck_pan");
  EXPECT_NE(found[0]["message"].get<std::string>().find(
                "expected to rise with neck_pan_deg (expect_direction +1), but it falls"),
            std::string::npos)
      << found[0]["message"];
}

// A mapping that only falls, however little, fails its expected direction: the slack
// for a fit's slight turn back applies only beside a real move the expected way.
TEST(Verify, AMappingThatFallsALittleAndNeverRisesFails) {
  const auto rig =
      hobby().replace("terms: { neck_pan_deg: 1.0 }", "terms: { neck_pan_deg: -0.001 }").write();
  const VerifyRun r = run_verify(rig.path(), {}, 1000);
  EXPECT_EQ(r.code, 1) << r.out;
  const auto found = failures(r, "static", "direction");
  ASSERT_EQ(found.size(), 1u) << r.out;
  EXPECT_EQ(found[0]["subject"], "neck_pan");
}

// The card's joint limits (-4..18 deg pitch) are the product's hard limit: an
// envelope widened beyond them fails verify with the values, even with
// `widen_override`, and `facectl run` refuses the rig.
TEST(Verify, AnEnvelopeWidenedBeyondTheCardFails) {
  const auto edited = hobby()
                          .replace("    pitch_deg: { min: 0, max: 15 }",
                                   "    widen_override: true\n    pitch_deg: { min: 0, max: 20 }")
                          .write();
  const std::string& rig = edited.path();
  const VerifyRun r = run_verify(rig, {}, 1000);
  EXPECT_EQ(r.code, 1) << r.out;
  const auto found = failures(r, "static", "rig");
  ASSERT_EQ(found.size(), 1u) << r.out;
  const std::string message = found[0]["message"];
  EXPECT_NE(message.find(rig + ":"), std::string::npos) << message;
  EXPECT_NE(message.find("mandible_envelope.pitch_deg: 0..20 deg, beyond the mandible's joint "
                         "limits -4..18 deg"),
            std::string::npos)
      << message;
  ConfigOverrides strict;
  strict.rig_path = rig;
  EXPECT_THROW(load_config(default_config_path(), strict), ConfigError);
}

// A CiA 402 drive counts in its bus's units, not in the actuator's (default,
// int16) `encoding`: a neck that turns ±340° is no encoding failure there,
// but is one on a custom CAN bus, whose int16 field carries ±327.67°.
TEST(Verify, ChecksEncodingsOnlyWhereTheDriverUsesThem) {
  EditedRig rig = default_rig();
  rig.replace("address: 4\n      position_deg: { min: -65, max: 65 }",
              "address: 4\n      position_deg: { min: -340, max: 340 }");
  const auto custom = rig.write();
  ConfigOverrides o;
  o.rig_path = custom.path();
  o.keep_problems = true;
  EXPECT_THROW(load_config(default_config_path(), o), ConfigError);  // the loader refuses it

  const auto cia402 =
      rig.replace("protocol: custom\n      values: int16", "protocol: cia402").write();
  const auto cfg = load_rig(cia402.path());
  const auto proof = verify::prove(cfg);
  const auto* f = find_failure(proof.findings, "encoding");
  EXPECT_EQ(f, nullptr) << f->subject << ": " << f->message;
}

TEST(Verify, ChecksCiA402EncodingsInTheDrivesInt32Counts) {
  const auto cia402 =
      default_rig().replace("protocol: custom\n      values: int16", "protocol: cia402").write();
  auto cfg = load_rig(cia402.path());
  EXPECT_EQ(find_failure(verify::prove(cfg).findings, "encoding"), nullptr);  // the bus's counts
  // neck_pan's own encoding: 65 deg at 5e7 counts per deg is beyond int32.
  for (ActuatorModel& a : cfg.built.model.actuators) {
    if (a.name == "neck_pan") a.encoding = {ActuatorEncoding::Raw::kInt32, 5e7, 0.0};
  }
  const auto proof = verify::prove(cfg);  // f points into it
  const auto* f = find_failure(proof.findings, "encoding");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->subject, "neck_pan");
  EXPECT_NE(f->message.find("does not fit raw int32: position -65 encodes to -3250000000"),
            std::string::npos)
      << f->message;
}

// Soundness: millions of admissible faces (random points of the box, made
// admissible by the tick's own projection, plus the box's extremes) never map
// outside the range the proof reported.
void expect_sound(const std::string& rig, long samples) {
  const auto cfg = load_rig(rig);
  const ControllerModel& m = cfg.built.model;
  const auto proof = verify::prove(cfg);
  const verify::Polytope set = verify::admissible_face_set(m);
  MappingWorkspace w = make_mapping_workspace(m.mapping);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::array<double, kMaxFaceSignals> face{};
  std::array<double, kMaxActuators> out{};
  for (long s = 0; s < samples; ++s) {
    const bool corner = s % 4 == 0;
    for (std::size_t j = 0; j < set.size(); ++j) {
      const double t = corner ? static_cast<double>(rng() % 2) : u(rng);
      face[j] = set.lo[j] + t * (set.hi[j] - set.lo[j]);
    }
    m.face_constraints.project(face.data());
    map_to_actuators(m.mapping, w, face, out);
    for (std::size_t i = 0; i < m.actuators.size(); ++i) {
      const auto& r = proof.actuators[i];
      const double scale = r.unit == "deg" ? 180.0 / M_PI : 1e3;
      const double x = out[i] * scale;
      const double eps = 1e-9 * (1.0 + std::fabs(x));
      ASSERT_GE(x, r.lo - eps) << r.name << " at sample " << s;
      ASSERT_LE(x, r.hi + eps) << r.name << " at sample " << s;
    }
  }
}

TEST(Verify, TheStaticProofIsSoundOnTheDefaultRig) {
  expect_sound(kSource + "/config/rigs/default.yaml", testing::sample_count(2'000'000));
}

TEST(Verify, TheStaticProofIsSoundOnTheHobbyRig) {
  expect_sound(kSource + "/config/rigs/hobby.yaml", testing::sample_count(1'000'000));
}

// The proof's witnesses on the channels that read control points. Each is an
// admissible face (inside the box and every coupled face limit the set holds),
// and the rig's real mapping takes it to the proven end within the branch and
// bound's tolerance: the proof's variables (muscles, jaw, eyelids) and the face
// layout's signals correspond, else a witness maps elsewhere. Returns the
// point channels checked.
int expect_point_witnesses_attain(const LoadedConfig& cfg, const verify::StaticProof& proof) {
  const ControllerModel& m = cfg.built.model;
  const verify::Polytope set = verify::admissible_face_set(m);
  MappingWorkspace w = make_mapping_workspace(m.mapping);
  std::array<double, kMaxFaceSignals> face{};
  std::array<double, kMaxActuators> out{};
  int checked = 0;
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    const bool reads_points = std::any_of(m.mapping.points.begin(), m.mapping.points.end(),
                                          [&](const PointTerm& p) { return p.actuator == i; });
    if (!reads_points) continue;
    const std::string& name = m.actuators[i].name;
    const auto r = std::find_if(proof.actuators.begin(), proof.actuators.end(),
                                [&](const verify::ActuatorRange& a) { return a.name == name; });
    if (r == proof.actuators.end()) {
      ADD_FAILURE() << name << ": no proven range";
      continue;
    }
    ++checked;
    EXPECT_EQ(r->method, "branch and bound on the reduced model") << name;
    const double scale = r->unit == "deg" ? 180.0 / M_PI : 1e3;
    const double tol = (verify::BoundOptions{}.tolerance + 1e-9) * scale;  // YAML unit
    for (const auto& [x, end, which] :
         {std::tuple{&r->at_lo, r->lo, "lo"}, std::tuple{&r->at_hi, r->hi, "hi"}}) {
      const std::string at = name + " at " + which;
      if (x->size() != set.size()) {
        ADD_FAILURE() << at << ": a witness of " << x->size() << " signals";
        continue;
      }
      for (std::size_t j = 0; j < set.size(); ++j) {
        EXPECT_GE((*x)[j], set.lo[j] - 1e-12) << at << ", " << m.layout.signal(j).name;
        EXPECT_LE((*x)[j], set.hi[j] + 1e-12) << at << ", " << m.layout.signal(j).name;
        face[j] = (*x)[j];
      }
      for (std::size_t k = 0; k < set.rows.size(); ++k) {
        double lhs = 0.0;
        for (std::size_t j = 0; j < set.size(); ++j) lhs += set.rows[k][j] * (*x)[j];
        EXPECT_LE(lhs, set.rhs[k] + 1e-9) << at << ": coupled face limit " << k;
      }
      map_to_actuators(m.mapping, w, face, out);
      EXPECT_NEAR(out[i] * scale, end, tol) << at << ": " << verify::describe_face(m, *x);
    }
  }
  return checked;
}

// The default rig and its proof, shared by the tests below (2.5 s each time).
struct ProvenRig {
  LoadedConfig cfg;
  verify::StaticProof proof;
};
const ProvenRig& proven_default_rig() {
  static const auto r = [] {
    auto p =
        std::make_unique<ProvenRig>(ProvenRig{load_rig(kSource + "/config/rigs/default.yaml"), {}});
    p->proof = verify::prove(p->cfg);
    return p;
  }();
  return *r;
}

TEST(Verify, PointChannelWitnessesAreAdmissibleAndAttainTheProvenEnds) {
  const ProvenRig& rig = proven_default_rig();
  EXPECT_EQ(expect_point_witnesses_attain(rig.cfg, rig.proof), 10);  // brows, cheeks, lip corners
}

// The default rig's outer brows follow fdp_4_5/4_6 through the reduced model, whose fit
// turns back by 0.14 and 0.17 deg (of a 90 deg range) as frontalis_outer nears 1: a
// warning that names the amount, not a failure.
TEST(Verify, AFitsSlightTurnBackIsAWarning) {
  const verify::StaticProof& proof = proven_default_rig().proof;
  EXPECT_EQ(find_failure(proof.findings, "direction"), nullptr);
  int slight = 0;
  for (const verify::Finding& f : proof.findings) {
    if (f.check != "direction") continue;
    EXPECT_EQ(f.severity, verify::Finding::Severity::kWarn) << f.message;
    EXPECT_NE(f.message.find("falls slightly (by at most 0.1"), std::string::npos) << f.message;
    slight += f.subject == "brow_outer_l" || f.subject == "brow_outer_r";
  }
  EXPECT_EQ(slight, 2);
}

// The slack is small: with three times the gain, the same turn back (0.41 deg of 90) is
// past it, and the outer brow fails its expected direction.
TEST(Verify, ATurnBackPastTheSlackFails) {
  const auto rig = default_rig()
                       .replace("- { point: fdp_4_5, axis: [0, 1, 0], gain: 2.4 }",
                                "- { point: fdp_4_5, axis: [0, 1, 0], gain: 7.2 }")
                       .write();
  const auto proof = verify::prove(load_rig(rig.path()));
  const auto* f = find_failure(proof.findings, "direction");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->subject, "brow_outer_l");
  EXPECT_EQ(f->message.find("slightly"), std::string::npos) << f->message;
}

// The same slack the other way: a servo mounted the other way round (the brow down for a
// rising command) expected to fall, whose fit turns back up as slightly, is a warning that
// says it rises.
TEST(Verify, AFitsSlightTurnBackOnAFallingMappingIsAWarning) {
  const auto rig = default_rig()
                       .replace("expect_direction: { frontalis_outer_l: +1 }",
                                "expect_direction: { frontalis_outer_l: -1 }")
                       .replace("- { point: fdp_4_5, axis: [0, 1, 0], gain: 2.4 }",
                                "- { point: fdp_4_5, axis: [0, -1, 0], gain: 2.4 }")
                       .write();
  const auto proof = verify::prove(load_rig(rig.path()));
  EXPECT_EQ(find_failure(proof.findings, "direction"), nullptr);
  const auto it = std::find_if(proof.findings.begin(), proof.findings.end(), [](const auto& f) {
    return f.check == "direction" && f.subject == "brow_outer_l";
  });
  ASSERT_NE(it, proof.findings.end());
  EXPECT_EQ(it->severity, verify::Finding::Severity::kWarn);
  EXPECT_NE(it->message.find("expected to fall with frontalis_outer_l (expect_direction -1), "
                             "but it rises slightly (by at most 0.1"),
            std::string::npos)
      << it->message;
}

// A coupled face limit over an eyelid and a brow muscle: the inner brow may not
// rise fully with the lid closing (frontalis_inner_l + eyelid_closure_l <= 0.5).
// The brow servo's proven range honours it: its top, where the frontalis pulls
// fully, is cut, its bottom stays, and the witness keeps to the limit.
TEST(Verify, ACoupledLimitOverAnEyelidNarrowsTheBrowChannel) {
  const std::string limit =
      "  coupled_limits:\n"
      "    - name: brow_lid_l\n"
      "      face: { frontalis_inner_l: 1, eyelid_closure_l: 1 }\n"
      "      max: 0.5\n";
  const auto rig = default_rig().replace("  coupled_limits:\n", limit).write();
  const auto cfg = load_rig(rig.path());
  ASSERT_TRUE(cfg.built.problems.empty()) << cfg.built.problems.front();
  const verify::StaticProof& base = proven_default_rig().proof;
  const auto proof = verify::prove(cfg);
  auto brow = [](const verify::StaticProof& p) {
    return *std::find_if(p.actuators.begin(), p.actuators.end(),
                         [](const verify::ActuatorRange& a) { return a.name == "brow_inner_l"; });
  };
  const verify::ActuatorRange wide = brow(base), narrow = brow(proof);
  const ControllerModel& m = cfg.built.model;
  const std::size_t frontalis = *m.layout.find("frontalis_inner_l");
  const std::size_t lid = *m.layout.find("eyelid_closure_l");
  auto within_limit = [&](const std::vector<double>& x) {
    return x[frontalis] + x[lid] <= 0.5 + 1e-9;
  };
  // The unconstrained top lies beyond the limit, so the limit must cut it.
  ASSERT_FALSE(within_limit(wide.at_hi)) << verify::describe_face(m, wide.at_hi);
  const double tol = (verify::BoundOptions{}.tolerance + 1e-9) * 180.0 / M_PI;
  EXPECT_LT(narrow.hi, wide.hi - 1.0) << "deg";
  EXPECT_GE(narrow.lo, wide.lo - tol);
  EXPECT_TRUE(within_limit(narrow.at_hi)) << verify::describe_face(m, narrow.at_hi);
  EXPECT_TRUE(within_limit(narrow.at_lo)) << verify::describe_face(m, narrow.at_lo);
  EXPECT_EQ(expect_point_witnesses_attain(cfg, proof), 10);
  std::printf("brow_inner_l: [%.4g, %.4g] deg without the limit, [%.4g, %.4g] with it\n", wide.lo,
              wide.hi, narrow.lo, narrow.hi);
}

}  // namespace
}  // namespace facectl
