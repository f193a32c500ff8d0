// Writes the synthetic test heads of test_heads.hpp to tests/data/heads/<name>/skin.obj:
//   make_test_heads <default head dir> <tests/data/heads>
// (built as target make_test_heads; the files are committed, this makes them again).
#include <cstdio>
#include <filesystem>

#include "facectl/face/obj_io.hpp"
#include "test_heads.hpp"

int main(int argc, char** argv) {
  using namespace facectl::face;
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_test_heads <default head dir> <output dir>\n");
    return 2;
  }
  const HeadSpec source = load_head_spec(argv[1]);
  for (const testing::HeadWarp& w : testing::test_head_warps()) {
    const std::filesystem::path dir = std::filesystem::path(argv[2]) / w.name;
    std::filesystem::create_directories(dir);
    const TriMesh m = testing::make_test_head(source, w);
    write_obj((dir / "skin.obj").string(), m, w.units);
    std::printf("%s: %zu vertices, %zu triangles\n", (dir / "skin.obj").c_str(), m.v.size(),
                m.tris.size());
  }
  return 0;
}
