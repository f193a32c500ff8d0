#include <gtest/gtest.h>
#include <chrono>
#include <cstdio>
#include "facectl/face/face_model.hpp"
using namespace facectl::face;
static void run(HeadSpec s, const char* label) {
  FaceModel m = build_face_model(s);
  FaceData d = make_face_data(m);
  std::vector<double> c(s.commanded.size(), 0.0);
  FaceInput in; in.contractions = c;
  double maxd = 0, maxm = 0;
  for (int i = 0; i < 100; ++i) step_face(m, d, in);
  for (size_t i = 0; i < d.skin_x.size(); ++i) maxd = std::max(maxd, (d.skin_x.get(i) - m.skin.v.get(i)).norm());
  for (size_t i = 0; i < d.muscles.size(); ++i) maxm = std::max(maxm, (d.muscles.get(i) - m.muscle_rest.get(i)).norm());
  std::printf("%-20s skin drift %.4f mm muscle drift %.4f mm\n", label, maxd * 1e3, maxm * 1e3);
}
TEST(Probe, Build) {
  HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  run(s, "all");
  HeadSpec a = s; a.skin.volume = 0; run(a, "no skin vol");
  a = s; a.skin.bending = 0; run(a, "no skin bend");
  a = s; a.sheet.bend = 0; a.sphincter.bend = 0; run(a, "no muscle bend");
  a = s; a.sheet.volume = 0; a.sphincter.volume = 0; run(a, "no muscle vol");
  a = s; a.skin.damping = 1; run(a, "damping 1");
}
TEST(Probe, Bend) {
  Points p;
  p.push_back(Vec3(0,0,0)); p.push_back(Vec3(1,0,0)); p.push_back(Vec3(0.5,1,0)); p.push_back(Vec3(0.5,-1,0.3));
  BendingConstraints b; b.add(0,1,2,3, 3.0, 1.0);
  std::vector<double> w(4,1.0);
  for (int i=0;i<5;++i){ double a = bending_angle(p,0,1,2,3); project(b,p,w); std::printf("angle %.5f -> %.5f (rest 3.0)\n", a, bending_angle(p,0,1,2,3)); }
}
