// Bad input names file:line, what was expected and what was found.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "default_head.hpp"
#include "facectl/face/expression_library.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/obj_io.hpp"

namespace facectl::face {
namespace {

namespace fs = std::filesystem;

std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path p =
      fs::temp_directory_path() / ("facectl_face_" + std::to_string(getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ObjInput, ShortVertexNamesFileAndLine) {
  const std::string p = write_temp("short.obj", "# c\nv 1 2 3\nv 1 2\nf 1 2 3\n");
  const std::string e = error_of([&] { read_obj(p, 1); });
  EXPECT_NE(e.find(p + ":3:"), std::string::npos) << e;
  EXPECT_NE(e.find("expected 'v x y z', found 2 values"), std::string::npos) << e;
}

TEST(ObjInput, BadNumberAndIndexAreNamed) {
  const std::string p = write_temp("bad.obj", "v 1 2 x\n");
  EXPECT_NE(error_of([&] { read_obj(p, 1); }).find(":1: expected a number, found 'x'"),
            std::string::npos);
  const std::string q = write_temp("idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  const std::string e = error_of([&] { read_obj(q, 1); });
  EXPECT_NE(e.find(q + ":4:"), std::string::npos) << e;
  EXPECT_NE(e.find("out of range 1..3"), std::string::npos) << e;
}

TEST(ObjInput, RoundTripsTheDefaultSkin) {
  const FaceModel& m = testing::default_model();
  const std::string p =
      (fs::temp_directory_path() / ("facectl_face_rt_" + std::to_string(getpid()) + ".obj"))
          .string();
  write_obj(p, m.skin, 0.01);
  TriMesh back = read_obj(p, 0.01);
  ASSERT_EQ(back.v.size(), m.skin.v.size());
  ASSERT_EQ(back.tris, m.skin.tris);
  for (std::size_t i = 0; i < back.v.size(); ++i)
    EXPECT_LT((back.v.get(i) - m.skin.v.get(i)).norm(), 1e-9);
}

// Copies the default head into a temp folder with one file replaced.
std::string head_with(const std::string& file, const std::string& text) {
  const fs::path dir =
      fs::temp_directory_path() / ("facectl_face_head_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::copy(FACECTL_DEFAULT_HEAD_DIR, dir);
  std::ofstream(dir / file) << text;
  return dir.string();
}

TEST(HeadInput, BadMuscleKeyNamesFileLineAndKey) {
  const std::string dir =
      head_with("muscles.yaml", "muscles:\n  - name: x\n    kind: sheet\n    layer: deep\n");
  const std::string e = error_of([&] { load_head_spec(dir); });
  EXPECT_NE(
      e.find(
          "muscles.yaml:4:12: key 'layer': expected an integer layer (0 = deepest), found 'deep'"),
      std::string::npos)
      << e;
}

TEST(HeadInput, UnknownLandmarkIsNamed) {
  const std::string dir = head_with("muscles.yaml",
                                    "muscles:\n  - name: x\n    kind: sheet\n    layer: 0\n    "
                                    "grid: [4, 2]\n    thickness_mm: 2\n"
                                    "    origin: [{ at: fdp_99_1 }, { at: fdp_2_1 }]\n    "
                                    "insertion: [{ at: fdp_2_1 }, { at: fdp_2_1 }]\n");
  const std::string e = error_of([&] { load_head_spec(dir); });
  EXPECT_NE(e.find("muscles.yaml:7:"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a landmark defined in landmarks.yaml, found 'fdp_99_1'"),
            std::string::npos)
      << e;
}

TEST(HeadInput, YamlSyntaxErrorIsLocated) {
  const std::string dir = head_with("landmarks.yaml", "landmarks:\n  fdp_2_1: { vertex: 152\n");
  EXPECT_NE(error_of([&] { load_head_spec(dir); }).find("landmarks.yaml:"), std::string::npos);
}

TEST(ExpressionInput, UnknownMuscleAndRangeAreNamed) {
  const std::string p =
      write_temp("lib.yaml", "expressions:\n  joy:\n    muscles: { zygomaticus_l: 0.5 }\n");
  std::string e = error_of([&] { load_expression_library(p, testing::default_spec()); });
  EXPECT_NE(e.find(p + ":3:16: muscle 'zygomaticus_l': expected a commanded muscle"),
            std::string::npos)
      << e;
  const std::string q =
      write_temp("lib2.yaml", "expressions:\n  jaw:\n    mandible: { pitch_deg: 30 }\n");
  e = error_of([&] { load_expression_library(q, testing::default_spec()); });
  EXPECT_NE(e.find(q + ":3:28: key 'pitch_deg': expected -4"), std::string::npos) << e;
}

}  // namespace
}  // namespace facectl::face
