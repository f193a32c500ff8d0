// `facectl face fit-head` on a real head mesh that nobody here made: the head of Debian's
// libcgal-demo (tests/data/heads/cgal_head, CC0). A whole head, facing -x. The fit aligns
// bounding boxes without turning the mesh, so such a head was fitted "converged" with the
// default face's chin on its neck, or its face on a cheek. It is now refused, saying what
// to do, and it fits once turned and cut to the face.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "default_head.hpp"
#include "facectl/face/face_finder.hpp"
#include "facectl/face/head_fit.hpp"
#include "facectl/face/head_writer.hpp"
#include "facectl/face/input_error.hpp"
#include "facectl/face/obj_io.hpp"

namespace facectl::face {
namespace {

using testing::default_spec;

// Read as centimetres: its unit is not recorded, and the fit is scale-free. It looks along
// -x; turned_about_y (face_finder.hpp) by +90 it looks along +z.
TriMesh cgal_head() {
  return read_obj(FACECTL_CONFIG_DIR "/../tests/data/heads/cgal_head/head.obj", 0.01);
}

// What a user would cut in a mesh editor: the front of the head from the forehead to
// below the chin (y 5.5 to 16.5 and z over 1.2 in the file's unit, the nose tip at y 11.1,
// z 7.3), without the neck and the back of the head.
TriMesh cut_to_face(const TriMesh& m) {
  TriMesh out;
  out.v = m.v;  // vertices no triangle uses are left out of the fit
  auto inside = [&](int i) { return m.v.y[i] >= 0.055 && m.v.y[i] <= 0.165 && m.v.z[i] > 0.012; };
  for (const Tri& t : m.tris)
    if (inside(t[0]) && inside(t[1]) && inside(t[2])) out.tris.push_back(t);
  return out;
}

std::string refusal(const TriMesh& m) {
  try {
    check_head_mesh(m, "head.obj");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HeadFitOnARealMesh, AsShippedItLooksAlongXAndIsRefused) {
  const std::string why = refusal(cgal_head());
  EXPECT_NE(why.find("head.obj: not mirror-symmetric about any upright plane through its "
                     "frontmost point"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("is it looking along x?"), std::string::npos) << why;
}

TEST(HeadFitOnARealMesh, TurnedItIsAWholeHeadAndIsRefused) {
  const std::string why = refusal(turned_about_y(cgal_head(), 90));
  EXPECT_NE(why.find("head.obj: 91.3 mm wide (x) and 140.0 mm deep (z): a whole head, not a "
                     "face"),
            std::string::npos)
      << why;
}

// The fit of a face cut from the CGAL head, by hand or by find_face: nothing reported,
// its own eye holes found, the landmarks where a face has them, and a folder that builds.
void expect_fits_as_a_face(const TriMesh& face, const std::string& name) {
  ASSERT_EQ(refusal(face), "");
  const TriMesh source = read_obj(default_spec().skin_file, default_spec().skin_scale);
  const HeadFit fit = fit_head(default_spec(), source, face, HeadFitOptions{});
  for (const std::string& p : fit.problems) ADD_FAILURE() << p;
  EXPECT_TRUE(fit.converged);
  // Its eye holes are found as the eye openings.
  int own_holes = 0;
  for (const std::string& n : fit.opening_notes)
    own_holes += n.find("the mesh's own hole") != std::string::npos ? 1 : 0;
  EXPECT_EQ(own_holes, 2);
  std::map<std::string, Vec3> at;
  for (const PlacedLandmark& l : fit.landmarks) at[l.name] = l.fitted;
  // The nose tip is the frontmost point of this face (of the vertices it still uses).
  double front = -1;
  Vec3 nose;
  for (const Tri& t : face.tris)
    for (int i : t)
      if (face.v.z[i] > front) front = face.v.z[i], nose = face.v.get(i);
  EXPECT_LT((at.at("fdp_9_3") - nose).norm(), 0.003);
  // The mouth corners and the outer eye corners sit either side of the nose, level with
  // each other, and in the right order down the face.
  for (const auto& [l, r] : {std::pair{"fdp_8_3", "fdp_8_4"}, {"fdp_3_7", "fdp_3_8"}}) {
    EXPECT_NEAR(at.at(l).x() - nose.x(), nose.x() - at.at(r).x(), 0.003) << l;
    EXPECT_NEAR(at.at(l).y(), at.at(r).y(), 0.003) << l;
  }
  EXPECT_GT(at.at("fdp_3_7").y(), nose.y());
  EXPECT_LT(at.at("fdp_8_3").y(), nose.y());
  EXPECT_LT(at.at("fdp_2_1").y(), at.at("fdp_8_3").y());
  // The folder it writes builds, as `face render` and `face reduce` build it.
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  const std::string obj = (dir.parent_path() / (name + ".obj")).string();
  write_obj(obj, face, 0.01);
  write_head_folder(dir.string(), fit.spec, {obj, "cm", FACECTL_DEFAULT_HEAD_DIR, name});
  const FaceModel m = build_face_model(load_head_spec(dir.string()));
  EXPECT_EQ(m.skin.v.size(), face.v.size());
}

TEST(HeadFitOnARealMesh, CutToTheFaceItFits) {
  expect_fits_as_a_face(cut_to_face(turned_about_y(cgal_head(), 90)), "cgal_head_cut");
}

// As shipped (a whole head looking along -x), turned to look along +x, and turned by an
// angle between the finder's steps: find_face turns it back and cuts the face, which then
// fits as the hand-cut face does.
TEST(HeadFitOnARealMesh, AsShippedItsFaceIsFoundAndFits) {
  const TriMesh source = read_obj(default_spec().skin_file, default_spec().skin_scale);
  for (const double extra : {0.0, 180.0, -52.5}) {
    const TriMesh head = turned_about_y(cgal_head(), extra);
    const FoundFace f = find_face(head, source, "head.obj");
    const std::string name = "cgal_head_found_" + std::to_string(static_cast<int>(extra + 360));
    RecordProperty(
        name, std::to_string(f.turn_degrees) + " kept " + std::to_string(f.kept_vertices) + " of " +
                  std::to_string(f.head_vertices) + " asymmetry " + std::to_string(f.asymmetry) +
                  " protrusion " + std::to_string(f.protrusion));
    EXPECT_NEAR(std::remainder(f.turn_degrees + extra - 90, 360.0), 0, 2.5) << extra;
    EXPECT_TRUE(f.cut);
    EXPECT_LT(f.kept_vertices, f.head_vertices * 3 / 4);
    expect_fits_as_a_face(f.mesh, name);
  }
}

// A face that already looks along +z is neither turned nor cut; a turned one is turned
// back and kept whole.
TEST(HeadFitOnARealMesh, TheDefaultFaceIsFoundAsItIs) {
  const TriMesh source = read_obj(default_spec().skin_file, default_spec().skin_scale);
  const FoundFace f = find_face(source, source, "skin.obj");
  EXPECT_EQ(f.turn_degrees, 0);
  EXPECT_FALSE(f.cut);
  EXPECT_EQ(f.kept_vertices, source.v.size());
  const FoundFace g = find_face(turned_about_y(source, -10), source, "skin.obj");
  EXPECT_NEAR(g.turn_degrees, 10, 2.5);
  EXPECT_FALSE(g.cut);  // turned back, not cut
  EXPECT_EQ(g.kept_vertices, source.v.size());
}

// A face turned about y is mirror-symmetric about a plane turned as much: the default
// skin turned by 10 degrees is refused with the angle, by 2.5 accepted.
TEST(HeadFitInput, RefusesAFaceTurnedMoreThanFiveDegrees) {
  const TriMesh source = read_obj(default_spec().skin_file, default_spec().skin_scale);
  auto turned = [&](double degrees) { return turned_about_y(source, degrees); };
  EXPECT_EQ(refusal(turned(2.5)), "");
  EXPECT_NE(refusal(turned(10))
                .find("head.obj: the face is turned 10.0 degrees about y (its "
                      "nose toward +x)"),
            std::string::npos)
      << refusal(turned(10));
  EXPECT_NE(refusal(turned(-10)).find("(its nose toward -x)"), std::string::npos)
      << refusal(turned(-10));
}

}  // namespace
}  // namespace facectl::face
