// face_warp_head FROM TO: writes the warped test head (warped_head.hpp) for the
// `facectl face clone` process test.
#include <cstdio>
#include <exception>

#include "warped_head.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: face_warp_head FROM_HEAD_DIR TO_DIR\n");
    return 2;
  }
  try {
    facectl::face::testing::write_warped_head(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "face_warp_head: %s\n", e.what());
    return 2;
  }
  return 0;
}
