#include <chrono>
#include <cstdio>
#include <cstdlib>
#include "facectl/face/reduced_face_model.hpp"
using namespace facectl::face;
int main(int argc, char** argv) {
  HeadSpec spec = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  FaceModel m = build_face_model(spec);
  ReduceOptions o;
  o.train_samples = argc > 1 ? std::atoi(argv[1]) : 150;
  o.test_samples = argc > 2 ? std::atoi(argv[2]) : 40;
  o.frames = argc > 3 ? std::atoi(argv[3]) : 250;
  ReduceReport r;
  auto t0 = std::chrono::steady_clock::now();
  build_reduced_model(m, o, &r);
  std::printf("train rms %.3f mm, test rms %.3f mm, max %.3f mm (%.1f s)\n", r.train_rms_mm, r.test_rms_mm, r.test_max_mm, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}
