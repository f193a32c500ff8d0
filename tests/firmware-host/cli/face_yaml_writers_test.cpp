// The YAML that `facectl face clone` and `facectl face place-actuators` write, read back:
// by the project's own loaders (expression library, visemes) or its YAML file reader (the
// rig snippet), every value exactly as written and names with a colon, quotes, a hash or
// a comma intact.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "control/envelope/mandible_envelope.hpp"
#include "control/units.hpp"
#include "facectl/face/yaml_file.hpp"
#include "firmware-host/cli/clone_head_ranges.hpp"
#include "firmware-host/cli/clone_yaml.hpp"
#include "firmware-host/cli/face_command_support.hpp"
#include "firmware-host/cli/placement_yaml.hpp"

namespace facectl {
namespace {

namespace fs = std::filesystem;

const std::string kOdd = "odd: #1 \"x\" 'y', [z]";

// The default head with its first commanded muscle renamed to kOdd.
face::HeadSpec odd_head() {
  face::HeadSpec h = face::load_head_spec(FACECTL_SOURCE_DIR "/config/heads/default");
  h.commanded[0] = kOdd;
  return h;
}

std::string write(const std::string& name, const std::string& text) {
  const fs::path p = fs::path(::testing::TempDir()) / name;
  face_cli::write_text_file(p.string(), text);
  return p.string();
}

// Values no short decimal holds, at the edges of the readers' ranges and in between.
std::vector<face::Expression> poses(const face::HeadSpec& h) {
  face::Expression a;
  a.name = kOdd;
  a.contractions.assign(h.commanded.size(), 0.0);
  a.contractions[0] = 1.0 / 3;
  a.contractions[1] = 1;
  a.contractions[2] = 0.1 + 0.2;
  a.contractions[3] = 1e-17;
  a.jaw.pitch_rad = kJawPitchMaxDeg * kDeg;
  a.jaw.yaw_rad = -kJawYawMaxDeg * kDeg / 3;
  a.jaw.protrusion_m = 1e-3 / 7;
  a.eyelid_closure[0] = 2.0 / 3;
  face::Expression b;
  b.name = "neutral";
  b.contractions.assign(h.commanded.size(), 0.0);
  b.jaw.pitch_rad = kJawPitchMinDeg * kDeg;
  b.eyelid_closure[1] = 0.7;
  return {a, b};
}

void expect_same(const face::Expression& read, const face::Expression& written) {
  EXPECT_EQ(read.name, written.name);
  EXPECT_EQ(read.contractions, written.contractions);
  EXPECT_EQ(read.jaw.pitch_rad, written.jaw.pitch_rad);
  EXPECT_EQ(read.jaw.yaw_rad, written.jaw.yaw_rad);
  EXPECT_EQ(read.jaw.protrusion_m, written.jaw.protrusion_m);
  EXPECT_EQ(read.eyelid_closure[0], written.eyelid_closure[0]);
  EXPECT_EQ(read.eyelid_closure[1], written.eyelid_closure[1]);
}

TEST(CloneYaml, LibraryReadsBackExactly) {
  const face::HeadSpec h = odd_head();
  const std::vector<face::Expression> ps = poses(h);
  const std::vector<face::PoseSequence> seqs = {{kOdd, 1.0 / 3, {kOdd, "neutral", kOdd}}};
  const std::string path = write(
      "clone_library.yaml", library_yaml(ps, h, seqs, "a comment: # 'with' \"quotes\"\nline 2"));
  const face::ExpressionLibrary lib = face::load_expression_library(path, h);
  ASSERT_EQ(lib.expressions.size(), ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) expect_same(lib.expressions[i], ps[i]);
  ASSERT_EQ(lib.sequences.size(), 1u);
  EXPECT_EQ(lib.sequences[0].name, kOdd);
  EXPECT_EQ(lib.sequences[0].period_s, 1.0 / 3);
  EXPECT_EQ(lib.sequences[0].poses, seqs[0].poses);
}

TEST(CloneYaml, VisemesReadBackExactlyWithTheirKeys) {
  const face::HeadSpec h = odd_head();
  std::vector<face::Expression> cloned = poses(h);
  std::vector<VisemePose> vs(2);
  vs[0].pose.name = kOdd;
  vs[0].index = 7;
  vs[0].phonemes = "a: \"b\" #c";
  vs[0].set_keys = {kOdd, "yaw_deg", "eyelid_closure_r"};  // set in the source
  vs[1].pose.name = "neutral";
  vs[1].set_keys = {h.commanded[5]};
  cloned[1].contractions[5] = 0;  // a set key the clone took to 0 stays in the file
  const std::string path = write("clone_visemes.yaml", visemes_yaml(vs, cloned, h, "visemes"));
  const std::vector<VisemePose> read = load_viseme_poses(path, h);
  ASSERT_EQ(read.size(), vs.size());
  for (std::size_t i = 0; i < vs.size(); ++i) {
    SCOPED_TRACE(i);
    expect_same(read[i].pose, cloned[i]);
    EXPECT_EQ(read[i].index, vs[i].index);
    EXPECT_EQ(read[i].phonemes, vs[i].phonemes);
  }
  EXPECT_NE(std::find(read[1].set_keys.begin(), read[1].set_keys.end(), h.commanded[5]),
            read[1].set_keys.end());
  EXPECT_NE(std::find(read[0].set_keys.begin(), read[0].set_keys.end(), "eyelid_closure_r"),
            read[0].set_keys.end());
}

// The clone's target ranges come from its head.yaml: here the lids narrowed to 0.2..0.6.
TEST(CloneHeadRanges, TakeTheEyelidRangeFromHeadYaml) {
  const fs::path dir = fs::path(::testing::TempDir()) / "narrow_lids";
  fs::remove_all(dir);
  fs::copy(FACECTL_SOURCE_DIR "/config/heads/default", dir, fs::copy_options::recursive);
  std::ifstream in(dir / "head.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string from = "eyelid_closure: { min: 0, max: 1 }";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "eyelid_closure: { min: 0.2, max: 0.6 }");
  face_cli::write_text_file((dir / "head.yaml").string(), text);
  face::MotionCloneOptions o;
  set_head_ranges(face::load_head_spec(dir.string()), o);
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(o.eyelid[side].min, 0.2);
    EXPECT_EQ(o.eyelid[side].max, 0.6);
  }
  EXPECT_EQ(o.jaw.pitch_max, 18 * kDeg);  // the default head's envelope
}

// The snippet is for a person: lengths to 0.01 mm, axes to 1e-4, errors to 0.001 mm.
TEST(PlacementYaml, ReadsBackRoundedForAPerson) {
  face::Placement p;
  face::PlacedActuator a;
  a.vertex = 42;
  a.landmark = kOdd;
  a.nearest_control_point = kOdd + "#2";
  a.control_point_distance_mm = 1.0 / 3;
  a.position_mm = face::Vec3(0.1 + 0.2, -1e-7, 123.456789012345678);
  a.axis = face::Vec3(1, 2, 3).normalized();
  a.travel_min_mm = -2.0 / 3;
  a.travel_max_mm = 15.000000000000002;
  p.actuators = {a, a};
  p.actuators[1].landmark.clear();
  face::ExpressionFit f;
  f.name = kOdd;
  f.rms_mm = 1.0 / 7;
  f.max_mm = 12.496;
  f.rms0_mm = 2.355;
  f.max0_mm = 1e-300;
  f.settled = false;
  p.fits = {f};
  const std::string path =
      write("placement.yaml", placement_yaml(p, "facectl face place-actuators"));
  const YAML::Node y = face::load_yaml_file(path);
  ASSERT_EQ(y["actuators"].size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const YAML::Node n = y["actuators"][i];
    EXPECT_EQ(n["point"].as<std::string>(), a.nearest_control_point);
    EXPECT_EQ(n["vertex"].as<int>(), a.vertex);
    EXPECT_EQ(n["landmark"].IsDefined(), i == 0);
    EXPECT_NEAR(n["control_point_distance_mm"].as<double>(), a.control_point_distance_mm, 0.005);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(n["position_mm"][c].as<double>(), a.position_mm[c], 0.005);
      EXPECT_NEAR(n["axis"][c].as<double>(), a.axis[c], 0.5e-4);
    }
    EXPECT_EQ(n["travel_mm"][0].as<double>(), -0.67);
    EXPECT_EQ(n["travel_mm"][1].as<double>(), 15);
    EXPECT_EQ(n["position_mm"][2].as<double>(), 123.46);
  }
  EXPECT_EQ(y["actuators"][0]["landmark"].as<std::string>(), kOdd);
  const YAML::Node e = y["errors"][kOdd];
  ASSERT_TRUE(e.IsMap());
  EXPECT_EQ(e["rms_mm"].as<double>(), 0.143);
  EXPECT_EQ(e["max_mm"].as<double>(), 12.496);
  EXPECT_EQ(e["rms_mm_no_actuators"].as<double>(), 2.355);
  EXPECT_EQ(e["max_mm_no_actuators"].as<double>(), 0);
  EXPECT_TRUE(e["unsettled"].as<bool>());
}

}  // namespace
}  // namespace facectl
