// load_yaml_file, the one reader of every YAML file facectl reads (issue 21):
// a repeated or non-plain key anywhere, a directory or an empty file is an
// error naming file:line:column, never a silent choice or a bare yaml-cpp
// or stream message.
#include "facectl/face/yaml_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

namespace fs = std::filesystem;

// The error for a file with `text`, the file's path replaced by F.
std::string error_for(const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("facectl_yaml_" + std::to_string(getpid()));
  std::ofstream(p) << text;
  std::string e = "no error";
  try {
    load_yaml_file(p.string());
  } catch (const InputError& err) {
    e = err.what();
    if (e.rfind(p.string(), 0) == 0) e.replace(0, p.string().size(), "F");
  }
  fs::remove(p);
  return e;
}

TEST(YamlFile, ARepeatedKeyNamesItsPathAndBothLines) {
  EXPECT_EQ(error_for("runtime:\n  rate_hz: 1000\n  rate_hz: 5\n"),
            "F:3:3: duplicate key 'runtime.rate_hz' (first at line 2)");
  EXPECT_EQ(error_for("a:\n  - { x: 1 }\n  - { y: 1, z: [{ k: 1, k: 2 }] }\n"),
            "F:3:25: duplicate key 'a[1].z[0].k' (first at line 3)");
  // Quoting does not make another key.
  EXPECT_EQ(error_for("k: 1\n\"k\": 2\n"), "F:2:1: duplicate key 'k' (first at line 1)");
}

TEST(YamlFile, TheFirstProblemInTheFileIsNamed) {
  EXPECT_EQ(error_for("a:\n  b: 1\n  b: 2\nc: 1\nc: 2\n"),
            "F:3:3: duplicate key 'a.b' (first at line 2)");
  EXPECT_EQ(error_for("a: 1\na: 2\nc:\n  b: 1\n  b: 2\n"),
            "F:2:1: duplicate key 'a' (first at line 1)");
}

TEST(YamlFile, AKeyThatIsNotAPlainNameIsNamed) {
  EXPECT_EQ(error_for("? [a, b]\n: 1\n"),
            "F:1:3: <top>: a mapping key must be a plain name, found a sequence");
  EXPECT_EQ(error_for("m:\n  ? { x: 1 }\n  : 2\n"),
            "F:2:5: m: a mapping key must be a plain name, found a mapping");
}

TEST(YamlFile, AliasesAreWalkedOnceAndMergeKeysStillLoad) {
  // Ten levels of ten aliases: 10^10 paths, each node walked once.
  std::string text = "l0: &l0 { a: 1 }\n";
  for (int i = 1; i <= 10; ++i) {
    const std::string prev = "*l" + std::to_string(i - 1);
    text += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [" + prev;
    for (int j = 1; j < 10; ++j) text += ", " + prev;
    text += "]\n";
  }
  EXPECT_EQ(error_for(text), "no error");
  EXPECT_EQ(error_for("base: &b { x: 1, x: 2 }\nuse: [*b, *b]\n"),
            "F:1:18: duplicate key 'base.x' (first at line 1)");
  // yaml-cpp reads `<<` as a key like any other: the same key in the base and
  // in the mapping that names it is no repeat.
  EXPECT_EQ(error_for("base: &b { x: 1 }\nuse:\n  <<: *b\n  x: 2\n"), "no error");
}

TEST(YamlFile, ADirectoryAnEmptyFileOrNoMappingIsNamed) {
  const std::string dir = fs::temp_directory_path().string();
  try {
    load_yaml_file(dir);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, expected a YAML file");
  }
  EXPECT_EQ(error_for(""), "F:1:1: expected a YAML mapping at the top level, found nothing");
  EXPECT_EQ(error_for("# only a comment\n"),
            "F:1:1: expected a YAML mapping at the top level, found nothing");
  EXPECT_EQ(error_for("- a\n"),
            "F:1:1: expected a YAML mapping at the top level, found a sequence");
}

}  // namespace
}  // namespace facectl::face
