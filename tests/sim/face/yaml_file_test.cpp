// load_yaml_file, the one reader of every YAML file facectl reads (issue 21):
// a repeated or non-plain key anywhere, a directory or an empty file is an
// error naming file:line:column, never a silent choice or a bare yaml-cpp
// or stream message.
#include "facectl/face/yaml_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
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
            "F:1:3: <top>: expected a plain name as mapping key, found a sequence");
  EXPECT_EQ(error_for("m:\n  ? { x: 1 }\n  : 2\n"),
            "F:2:5: m: expected a plain name as mapping key, found a mapping");
  EXPECT_EQ(error_for("m:\n  - a: 1\n  - ? [x]\n    : 2\n"),
            "F:3:7: m[1]: expected a plain name as mapping key, found a sequence");
}

TEST(YamlFile, AliasesAreWalkedOnce) {
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
}

TEST(YamlFile, AMergeKeyIsRefusedNotReadAsAKey) {
  // yaml-cpp would keep `<<` as a key and never bring x into `use`.
  EXPECT_EQ(error_for("base: &b { x: 1 }\nuse:\n  <<: *b\n  y: 2\n"),
            "F:3:3: use: YAML merge keys (<<) are not supported; write the keys out");
  // Quoted, it is a plain name.
  EXPECT_EQ(error_for("\"<<\": 1\n"), "no error");
}

TEST(YamlFile, ASecondDocumentIsRefused) {
  EXPECT_EQ(error_for("a: 1\n---\na: 2\n"),
            "F:2:1: expected one YAML document, found a second one here");
  EXPECT_EQ(error_for("a: 1\n---\n"), "F:2:1: expected one YAML document, found a second one here");
  EXPECT_EQ(error_for("---\na: 1\n...\n"), "no error");
  // A thousand documents are not all read to say so.
  std::string many = "a: 1\n";
  for (int i = 0; i < 1000; ++i) many += "---\nb: 2\n";
  EXPECT_EQ(error_for(many), "F:2:1: expected one YAML document, found a second one here");
}

TEST(YamlFile, AStrayCommaIsASyntaxErrorNotEndlessDocuments) {
  // yaml-cpp reads `,` at the top level as an empty document without moving
  // past it: YAML::LoadAll took memory until killed, YAML::Load returned null.
  // Found by runtime_config_fuzz (tests/fuzz/regressions/runtime_config).
  const std::string comma = "YAML syntax error: unexpected ',' outside [ ] or { }";
  EXPECT_EQ(error_for(",\"edoc"), "F:1:1: " + comma);
  EXPECT_EQ(error_for("# c\n  ,\n"), "F:2:3: " + comma);
  EXPECT_EQ(error_for("%YAML 1.2\n---\n,\n"), "F:3:1: " + comma);
  EXPECT_EQ(error_for("[a]\n,\n"), "F:2:1: " + comma);
  // After a byte-order mark, and in UTF-16, yaml-cpp's positions are not
  // byte offsets into the file; the error must still come out as one.
  EXPECT_EQ(error_for("\xEF\xBB\xBF,x"), "F:1:1: " + comma);
  std::string utf16("#\0", 2);
  for (int i = 0; i < 20; ++i) utf16 += "\x2D\x4E";  // U+4E2D
  utf16.append("\n\0,\0", 4);
  EXPECT_EQ(error_for(utf16), "F:2:1: " + comma);
}

TEST(YamlFile, ASecondNodeWithoutDashesIsASecondDocument) {
  EXPECT_EQ(error_for("[a]\nb: 1\n"), "F:2:1: expected one YAML document, found a second one here");
}

TEST(YamlFile, AFileOverTheBoundIsRefusedBeforeParsing) {
  std::string text = "a: 1\n# ";
  text.resize(kMaxYamlFileBytes + 1, 'x');
  EXPECT_EQ(error_for(text), "F: file is " + std::to_string(kMaxYamlFileBytes + 1) +
                                 " bytes, expected at most " + std::to_string(kMaxYamlFileBytes) +
                                 " for a YAML file");
  text.resize(kMaxYamlFileBytes);
  EXPECT_EQ(error_for(text), "no error");
}

TEST(YamlFile, AFifoIsRefusedWithoutOpeningIt) {
  const fs::path p = fs::temp_directory_path() / ("facectl_fifo_" + std::to_string(getpid()));
  ASSERT_EQ(mkfifo(p.c_str(), 0600), 0);
  try {
    load_yaml_file(p.string());  // would block forever in open() if it were opened
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), p.string() + ": is not a regular file, expected a YAML file");
  }
  fs::remove(p);
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
