#include <gtest/gtest.h>
#include <chrono>
#include <cstdio>
#include "facectl/face/face_model.hpp"
using namespace facectl::face;
TEST(Probe, Muscles) {
  HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  FaceModel m = build_face_model(s);
  FaceData d = make_face_data(m);
  const char* lms[] = {"fdp_8_3", "fdp_8_4", "fdp_8_1", "fdp_8_2", "fdp_4_1", "fdp_4_2", "fdp_4_5", "fdp_3_1", "fdp_2_1"};
  auto report = [&](const char* label, FaceInput in, int frames) {
    reset_face_data(m, d);
    Points before;
    for (int i = 0; i < frames; ++i) { if (i == frames - 10) before = d.skin_x; step_face(m, d, in); }
    double maxd = 0, conv = 0;
    for (size_t i = 0; i < d.skin_x.size(); ++i) { maxd = std::max(maxd, (d.skin_x.get(i) - m.skin.v.get(i)).norm()); conv = std::max(conv, (d.skin_x.get(i) - before.get(i)).norm()); }
    std::printf("%-40s max %5.2f conv10 %5.3f |", label, maxd * 1e3, conv * 1e3);
    for (auto l : lms) { int k = m.landmark_index(l); Vec3 dv = (landmark_position(m, d.skin_x, k) - landmark_position(m, m.skin.v, k)) * 1e3; std::printf(" %s(%.1f,%.1f,%.1f)", l + 4, dv.x(), dv.y(), dv.z()); }
    std::printf("\n");
  };
  std::vector<double> c(s.commanded.size(), 0.0);
  FaceInput in; in.contractions = c;
  for (size_t k = 0; k < s.commanded.size(); ++k) {
    if (s.commanded[k].back() == 'l') continue;
    std::fill(c.begin(), c.end(), 0.0); c[k] = 0.8;
    report(s.commanded[k].c_str(), in, 200);
  }
  std::fill(c.begin(), c.end(), 0.0);
  in.jaw.pitch_rad = 12 * M_PI / 180; report("jaw 12deg", in, 200);
  in.jaw = {}; in.eyelid_closure[0] = in.eyelid_closure[1] = 1; report("blink", in, 100);
}
TEST(Probe, Anchors) {
  HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  FaceModel m = build_face_model(s);
  for (size_t l = 0; l < m.landmark_names.size(); ++l) {
    int v = m.landmark_vertices[l][0];
    const SurfacePoint& sp = m.anchor_support[v];
    std::string who = "skull";
    if (sp.layer == Layer::kMuscle) for (auto& mu : m.muscles) if (sp.i0 >= mu.first && sp.i0 < mu.first + mu.particle_count()) who = mu.name;
    std::printf("anchor %s v%d -> %s infl %.2f\n", m.landmark_names[l].c_str(), v, who.c_str(), m.influence[v]);
  }
}
TEST(Probe, JawNoOris) {
  HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  std::erase_if(s.muscles, [](auto& m) { return m.name == "orbicularis_oris"; });
  FaceModel m = build_face_model(s);
  FaceData d = make_face_data(m);
  std::vector<double> c(s.commanded.size(), 0.0);
  FaceInput in; in.contractions = c; in.jaw.pitch_rad = 12 * M_PI / 180;
  for (int i = 0; i < 200; ++i) step_face(m, d, in);
  for (auto l : {"fdp_8_3", "fdp_8_4", "fdp_8_1", "fdp_8_2", "fdp_2_2", "fdp_2_3"}) { int k = m.landmark_index(l); Vec3 dv = (landmark_position(m, d.skin_x, k) - landmark_position(m, m.skin.v, k)) * 1e3; std::printf("noOris %s (%.1f,%.1f,%.1f)\n", l, dv.x(), dv.y(), dv.z()); }
  for (int v : {61, 291, 0, 17, 13, 14}) { auto& sp = m.anchor_support[v]; std::printf("v%d layer %d tri %d %d %d\n", v, int(sp.layer), sp.i0, sp.i1, sp.i2); }
}
TEST(Probe, Hits) {
  HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  FaceModel m = build_face_model(s);
  Points n; vertex_normals(m.skin.v, m.skin.tris, n);
  for (int v : {61, 107, 70}) {
    Vec3 p = m.skin.v.get(v), d = -n.get(v);
    std::printf("v%d p(%.1f %.1f %.1f)\n", v, p.x()*1e3, p.y()*1e3, p.z()*1e3);
    for (auto& mu : m.muscles) {
      int nb = mu.rows * mu.cols;
      double best = 1e9; Vec3 cen = Vec3::Zero();
      for (int i = 0; i < nb; ++i) cen += m.muscle_rest.get(mu.first + nb + i) / nb;
      for (auto& t : mu.surface) { if (t[0] < mu.first + nb) continue; double a, b; double h = ray_triangle(p, d, m.muscle_rest.get(t[0]), m.muscle_rest.get(t[1]), m.muscle_rest.get(t[2]), a, b); if (a >= -1e-9 && h > -1 && std::abs(h) < std::abs(best)) best = h; }
      if ((cen - p).norm() < 0.03) std::printf("  %-30s hit t=%.2f mm  top-centre dist %.1f mm\n", mu.name.c_str(), best * 1e3, (cen - p).norm() * 1e3);
    }
  }
}
TEST(Probe, Tri) {
  HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  FaceModel m = build_face_model(s);
  for (int t : {670, 56, 250}) { auto tr = m.skin.tris[t]; std::printf("tri %d: %d %d %d\n", t, tr[0], tr[1], tr[2]);
    for (int k = 0; k < 3; ++k) { int v = tr[k]; bool lid = false; for (size_t j = 0; j < m.lids.size(); ++j) if (m.lids.particle[j] == v) lid = true; Vec3 p = m.skin.v.get(v) * 1e3; std::printf("  v%d (%.1f %.1f %.1f) lid %d infl %.2f\n", v, p.x(), p.y(), p.z(), lid, m.influence[v]); } }
}
#include <random>
static int soak_count(const FaceModel& m, int frames, unsigned seed, bool teeth, bool only_jaw, bool only_muscles) {
  FaceData d = make_face_data(m);
  const std::size_t n = m.spec.commanded.size();
  std::vector<double> c(n, 0.0), goal(n, 0.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  FaceInput in; in.contractions = c; in.teeth_collision = teeth;
  MandiblePose jaw_goal;
  std::vector<Vec3> rest_n;
  for (const Tri& t : m.skin.tris) rest_n.push_back((m.skin.v.get(t[1]) - m.skin.v.get(t[0])).cross(m.skin.v.get(t[2]) - m.skin.v.get(t[0])));
  int bad = 0; std::vector<int> worst(m.skin.tris.size(), 0);
  for (int f = 0; f < frames; ++f) {
    if (f % 40 == 0) {
      for (auto& g : goal) g = (!only_jaw && u(rng) < 0.4) ? u(rng) : 0.0;
      jaw_goal = {(-4 + 22 * u(rng)) * M_PI / 180, (-5 + 10 * u(rng)) * M_PI / 180, 0.008 * u(rng)};
      if (only_muscles) jaw_goal = {};
    }
    for (std::size_t k = 0; k < n; ++k) c[k] += 0.1 * (goal[k] - c[k]);
    in.jaw.pitch_rad += 0.1 * (jaw_goal.pitch_rad - in.jaw.pitch_rad);
    in.jaw.yaw_rad += 0.1 * (jaw_goal.yaw_rad - in.jaw.yaw_rad);
    in.jaw.protrusion_m += 0.1 * (jaw_goal.protrusion_m - in.jaw.protrusion_m);
    step_face(m, d, in);
    for (std::size_t t = 0; t < m.skin.tris.size(); ++t) {
      const Tri& tr = m.skin.tris[t];
      const Vec3 nn = (d.skin_x.get(tr[1]) - d.skin_x.get(tr[0])).cross(d.skin_x.get(tr[2]) - d.skin_x.get(tr[0]));
      if (nn.dot(rest_n[t]) <= 0) { ++bad; ++worst[t]; }
    }
  }
  std::printf("teeth %d onlyjaw %d onlymus %d: inverted tri-frames %d; tris:", teeth, only_jaw, only_muscles, bad);
  for (size_t t = 0; t < worst.size(); ++t) if (worst[t]) std::printf(" %zu(%d)", t, worst[t]);
  std::printf("\n");
  return bad;
}
TEST(Probe, Soak) {
  HeadSpec s = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  FaceModel m = build_face_model(s);
  { HeadSpec s2 = s; s2.skin.anchor = 0.05; FaceModel m2 = build_face_model(s2); std::printf("anchor .05 "); soak_count(m2, 1000, 5, true, false, false); }
  { HeadSpec s2 = s; s2.skin.stretch = 0.5; FaceModel m2 = build_face_model(s2); std::printf("stretch .5 "); soak_count(m2, 1000, 5, true, false, false); }
  { HeadSpec s2 = s; s2.skin.damping = 1.0; FaceModel m2 = build_face_model(s2); std::printf("damp 1 "); soak_count(m2, 1000, 5, true, false, false); }
  { HeadSpec s2 = s; s2.skin.volume = 0; FaceModel m2 = build_face_model(s2); std::printf("vol 0 "); soak_count(m2, 1000, 5, true, false, false); }
  { HeadSpec s2 = s; s2.influence_falloff = 1; FaceModel m2 = build_face_model(s2); std::printf("infl wide "); soak_count(m2, 1000, 5, true, false, false); }
}
