#include "face_command_support.hpp"

#include <algorithm>

#include "firmware-host/config/config_location.hpp"

namespace facectl::face_cli {

FaceArgs default_face_args() {
  FaceArgs a;
  a.head = shipped_dirs().config + "/heads/default";
  a.library = shipped_dirs().config + "/expressions/library.yaml";
  return a;
}

void cap_frames_option(CLI::App* c, int default_cap) {
  c->get_option("--frames")
      ->description("cap on the full-model frames of each run to steady state")
      ->default_str(std::to_string(default_cap));
}

void passes_option(CLI::App* c, face::SolverPasses& passes) {
  c->add_option_function<int>(
       "--passes", [&passes](int n) { passes = {.skin = n, .muscle = n}; },
       "skin iterations and muscle passes a frame in each run to steady state (the same "
       "steady states as the head's solver, reached in fewer frames)")
      ->default_str(std::to_string(passes.muscle))
      ->check(CLI::Range(1, 100));
}

void add_common(CLI::App* c, FaceArgs& a) {
  c->add_option("--head", a.head, "head folder (face.yaml, landmarks, muscles)")
      ->capture_default_str();
  c->add_option("--library", a.library, "expression library YAML")->capture_default_str();
  c->add_option("--frames", a.frames, "full-model frames to steady state")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  auto* r = c->add_option("--resolution", a.resolution,
                          "skin vertex count: 0 = the base mesh, or more (edge splitting)")
                ->check(CLI::Range(0, 100000));
  if (a.resolution == kLargestVariant)
    r->default_str("the largest of face.yaml's variants");
  else
    r->capture_default_str();
}

face::FaceModel build_model(const face::HeadSpec& spec, int resolution) {
  int n = resolution;
  if (n == kLargestVariant)
    n = spec.variants.empty() ? 0 : *std::max_element(spec.variants.begin(), spec.variants.end());
  face::FaceModel m = face::build_face_model(spec, static_cast<std::size_t>(n));
  if (n != 0 && m.skin.v.size() != static_cast<std::size_t>(n))
    throw std::invalid_argument("--resolution " + std::to_string(n) +
                                ": must be 0, or at least the base mesh's " +
                                std::to_string(m.skin.v.size()) + " vertices");
  return m;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw face::InputError(path + ": cannot open file for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) throw face::InputError(path + ": write failed");
}

}  // namespace facectl::face_cli
