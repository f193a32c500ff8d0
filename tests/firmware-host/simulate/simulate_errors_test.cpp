// Bad and truncated FAP files and shows: a clear line-numbered error, exit 2,
// and no output (an existing output folder stays as it was).
#include <gtest/gtest.h>

#include "simulate_process.hpp"

namespace facectl {
namespace {

using testing::run_facectl;
using testing::source_path;
using testing::TempDir;

struct BadInput {
  std::string flag;  // --fap or --show
  std::string file;  // a FAP test file, or show text to write
  std::string text;  // empty: `file` is in tests/firmware-host/fap/files
  int line;
  std::string says = "expected";  // a part of the message
};

void PrintTo(const BadInput& b, std::ostream* os) {
  *os << b.flag << " " << b.file;
}

class SimulateBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(SimulateBadInput, GetsALineNumberedErrorAndWritesNothing) {
  const BadInput& b = GetParam();
  TempDir tmp;
  const std::string path =
      b.text.empty() ? std::string(FAP_TEST_FILES) + "/" + b.file : tmp / b.file;
  if (!b.text.empty()) testing::write_text(path, b.text);
  // A folder from an earlier run: it must survive a failed one untouched.
  std::filesystem::create_directories(tmp.path() / "kept");
  testing::write_text(tmp.path() / "kept/summary.json", "{}\n");
  for (const std::string& out : {tmp / "new", tmp / "kept"}) {
    const auto r = run_facectl(
        {"simulate", "--rig", source_path("config/rigs/default.yaml"), b.flag, path, "--out", out},
        tmp / "log");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(path + ":" + std::to_string(b.line) + ":"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find(b.says), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "new"));
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / ".new.partial"));
  EXPECT_EQ(testing::folder_contents(tmp.path() / "kept").size(), 1u);
  EXPECT_EQ(testing::read_text(tmp.path() / "kept/summary.json"), "{}\n");
}

INSTANTIATE_TEST_SUITE_P(Fap, SimulateBadInput,
                         ::testing::Values(BadInput{"--fap", "bad_version.fap", "", 1},
                                           BadInput{"--fap", "bad_header_fields.fap", "", 1},
                                           BadInput{"--fap", "mask_count.fap", "", 2},
                                           BadInput{"--fap", "non_numeric.fap", "", 4},
                                           BadInput{"--fap", "out_of_order.fap", "", 7},
                                           BadInput{"--fap", "truncated_frames.fap", "", 6},
                                           BadInput{"--fap", "truncated_values.fap", "", 5},
                                           BadInput{"--fap", "beyond_a_day.fap", "", 6},
                                           BadInput{"--fap", "slow_rate.fap", "", 6}));

INSTANTIATE_TEST_SUITE_P(
    Show, SimulateBadInput,
    ::testing::Values(
        BadInput{"--show", "bad_time.yaml",
                 "show:\n  name: bad\n  keyframes:\n    - { t: 0.0, expression: neutral }\n"
                 "    - { t: soon, expression: joy }\n",
                 5},
        BadInput{"--show", "truncated.yaml",
                 "show:\n  name: cut\n  keyframes:\n    - { t: 0.0, expression: neutral }\n"
                 "    - { t: 1.0, expression: jo",
                 5, "YAML syntax error"},
        BadInput{"--show", "unknown_expression.yaml",
                 "show:\n  name: bad\n  keyframes:\n    - { t: 0.0, expression: neutral }\n"
                 "    - { t: 1.0, expression: glee }\n",
                 5},
        // Issue 21: yaml-cpp kept both copies of a repeated key.
        BadInput{"--show", "repeated_key.yaml",
                 "show:\n  name: dup\n  keyframes:\n"
                 "    - { t: 0.0, expression: neutral, t: 1.0 }\n",
                 4, "duplicate key 'show.keyframes[0].t' (first at line 4)"},
        BadInput{"--show", "sequence_key.yaml", "show:\n  name: bad\n  ? [a, b]\n  : 1\n", 3,
                 "expected a plain name as mapping key"}));

// Issue 21: a directory as the show gave "basic_filebuf::underflow", naming
// no file.
TEST(SimulateDirectoryInput, IsNamed) {
  TempDir tmp;
  const auto r = run_facectl({"simulate", "--rig", source_path("config/rigs/default.yaml"),
                              "--show", tmp.path().string(), "--out", tmp / "new"},
                             tmp / "log");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(tmp.path().string() + ": is a directory, expected a YAML file"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "new"));
}

// One number must not fill the disk (issue 21): a day of show at the default
// telemetry rate could take gigabytes, so it is refused before anything is
// written, and the message names the flag that allows it.
TEST(SimulateOutputSize, ALongRunIsRefusedUnlessTheUserAllowsIt) {
  TempDir tmp;
  const std::string show = tmp / "day.yaml";
  testing::write_text(show,
                      "show:\n  name: day\n  keyframes:\n    - { t: 0 }\n    - { t: 86400 }\n");
  const auto r = run_facectl({"simulate", "--rig", source_path("config/rigs/default.yaml"),
                              "--show", show, "--out", tmp / "new"},
                             tmp / "log");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--out: the outputs of 86400 s of show could take up to "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("above --max-output-mb 1024; raise it"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "new"));
  // Render frames count as they are written: 2 s of them take about 3.6 MB,
  // against the 7 MB less 5.4 MB of telemetry bound.
  const auto rendered =
      run_facectl({"simulate", "--rig", source_path("config/rigs/default.yaml"), "--show",
                   source_path("config/shows/demo.yaml"), "--out", tmp / "new", "--duration", "2",
                   "--render", "--max-output-mb", "7", "--quiet"},
                  tmp / "log");
  EXPECT_EQ(rendered.exit_code, 2) << rendered.output;
  EXPECT_NE(rendered.output.find(" MB that --max-output-mb leaves them; raise it"),
            std::string::npos)
      << rendered.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "new"));
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / ".new.partial"));
  const auto longer =
      run_facectl({"simulate", "--rig", source_path("config/rigs/default.yaml"), "--show", show,
                   "--out", tmp / "new", "--duration", "90000", "--max-output-mb", "1e9"},
                  tmp / "log");
  EXPECT_EQ(longer.exit_code, 2) << longer.output;
  EXPECT_NE(longer.output.find("--duration: expected at most 86400"), std::string::npos)
      << longer.output;
}

// An installed program reads every data file beside its runtime file, not
// from the source tree: here a copy whose viseme table is broken.
TEST(SimulateConfig, ReadsTheVisemeTableBesideItsRuntimeFile) {
  TempDir tmp;
  std::string text = testing::read_text(source_path("config/facectl.yaml"));
  for (const std::string key : {"head: ", "rig: ", "expressions: ", "show: "}) {
    const auto at = text.find("\n" + key);
    ASSERT_NE(at, std::string::npos) << key;
    text.insert(at + 1 + key.size(), source_path("config").string() + "/");
  }
  testing::write_text(tmp / "facectl.yaml", text);
  std::filesystem::create_directories(tmp.path() / "fap");
  testing::write_text(tmp / "fap/visemes.yaml", "visemes: [\n");
  const auto r = run_facectl(
      {"simulate", "--rig", source_path("config/rigs/default.yaml"), "--config",
       tmp / "facectl.yaml", "--fap", source_path("config/fap/demo.fap"), "--out", tmp / "out"},
      tmp / "log");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(tmp / "fap/visemes.yaml:"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace facectl
