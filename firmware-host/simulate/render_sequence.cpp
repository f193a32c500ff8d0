#include "firmware-host/simulate/render_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "facectl/face/face_model.hpp"
#include "facectl/face/face_renderer.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/image.hpp"
#include "firmware-host/simulate/mapping_inverse.hpp"

namespace facectl {

namespace {

// Full-model frames per picture. The first picture starts from rest and takes
// what `facectl face render` uses; later ones start from the previous
// picture's state (warm start) and step until no skin vertex moves more than
// kSettledMotion in a frame, within [kMinWarmSteps, kMaxWarmSteps] (measured
// settling: docs/SIMULATE.md, "Render frames").
constexpr int kFirstSteps = 300;
constexpr int kMinWarmSteps = 10;
constexpr int kMaxWarmSteps = 60;
constexpr double kSettledMotion = 1e-5;  // m
constexpr int kDividerWidth = 4;
constexpr std::uint8_t kDividerGrey = 60;

std::string head_dir(const HeadConfig& head) {
  const std::size_t slash = head.file.find_last_of('/');
  return slash == std::string::npos ? "." : head.file.substr(0, slash);
}

// One view: the full face model, its state carried from picture to picture.
struct FaceView {
  face::FaceData data;
  std::vector<double> contractions;
  face::Points previous;  // skin before the last step
};

double largest_motion(const face::Points& a, const face::Points& b) {
  double most = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) most = std::max(most, (a.get(i) - b.get(i)).norm());
  return most;
}

}  // namespace

struct RenderSequence::State {
  std::filesystem::path out_dir;
  RenderOptions options;
  std::vector<std::string> frames;
  std::uint64_t bytes = 0;  // of the frames written
  ControllerModel model;    // a copy: the sequence may outlive the caller's config
  face::FaceModel face;
  FaceView left, right;
  MappingInverse inverse;
  std::unique_ptr<MappingInverseWorkspace> workspace;
  std::array<double, kMaxFaceSignals> commanded{}, inverted{};
  std::optional<std::size_t> eyelid_l, eyelid_r;

  // Steps one view towards a face (within the admissible box).
  void settle(FaceView& view, const std::array<double, kMaxFaceSignals>& signals,
              bool first) const {
    const FaceLayout& layout = model.layout;
    for (std::size_t k = 0; k < layout.muscle_count(); ++k) {
      view.contractions[k] = signals[k];
    }
    face::FaceInput in;
    in.contractions = view.contractions;
    in.jaw = {signals[layout.jaw_pitch()], signals[layout.jaw_yaw()],
              signals[layout.jaw_protrusion()]};
    if (eyelid_l) in.eyelid_closure[0] = signals[*eyelid_l];
    if (eyelid_r) in.eyelid_closure[1] = signals[*eyelid_r];
    if (first) {
      for (int i = 0; i < kFirstSteps; ++i) face::step_face(face, view.data, in);
      return;
    }
    for (int i = 1;; ++i) {
      view.previous = view.data.skin_x;
      face::step_face(face, view.data, in);
      const bool settled = largest_motion(view.previous, view.data.skin_x) <= kSettledMotion;
      if (i >= kMaxWarmSteps || (i >= kMinWarmSteps && settled)) return;
    }
  }
};

RenderSequence::RenderSequence(const LoadedConfig& config, const std::filesystem::path& out_dir,
                               RenderOptions options)
    : state_(std::make_unique<State>()) {
  if (options.width < 16 || options.height < 16 || !(options.fps > 0)) {
    throw std::invalid_argument("render: expected a picture of at least 16x16 pixels and fps > 0");
  }
  State& s = *state_;
  s.out_dir = out_dir;
  s.options = options;
  s.model = config.built.model;
  s.face = face::build_face_model(face::load_head_spec(head_dir(config.head)));
  for (FaceView* v : {&s.left, &s.right}) {
    v->data = face::make_face_data(s.face);
    v->contractions.assign(s.model.layout.muscle_count(), 0.0);
  }
  if (s.face.spec.commanded.size() != s.model.layout.muscle_count()) {
    throw std::invalid_argument(config.head.file +
                                ": the face model's commanded muscles differ from head.muscles");
  }
  s.inverse = make_mapping_inverse(s.model);
  s.commanded = s.model.neutral;
  s.workspace =
      std::make_unique<MappingInverseWorkspace>(make_mapping_inverse_workspace(s.inverse));
  s.eyelid_l = s.model.layout.find("eyelid_closure_l");
  s.eyelid_r = s.model.layout.find("eyelid_closure_r");
  std::filesystem::create_directories(out_dir / "frames");
}

RenderSequence::~RenderSequence() = default;

void RenderSequence::add_frame(std::span<const double> face_values,
                               std::span<const double> positions) {
  State& s = *state_;
  if (face_values.size() < s.model.layout.size() || positions.size() < s.model.actuators.size()) {
    throw std::invalid_argument("render: expected " + std::to_string(s.model.layout.size()) +
                                " face values and " + std::to_string(s.model.actuators.size()) +
                                " actuator positions, found " + std::to_string(face_values.size()) +
                                " and " + std::to_string(positions.size()));
  }
  // The command as the controller's sanitiser and envelope would take it: a
  // non-finite value holds the last good one, the rest is clamped to the box.
  for (std::size_t k = 0; k < s.inverse.signals; ++k) {
    if (std::isfinite(face_values[k])) {
      s.commanded[k] = std::clamp(face_values[k], s.inverse.lower[k], s.inverse.upper[k]);
    }
  }
  invert_mapping(s.inverse, *s.workspace, positions, s.inverted);
  const bool first = s.frames.empty();
  s.settle(s.left, s.commanded, first);
  s.settle(s.right, s.inverted, first);

  const face::RenderOptions view{face::View::kFront, s.options.width, s.options.height, false};
  const face::Image left = face::render_face(s.face, s.left.data, view);
  const face::Image right = face::render_face(s.face, s.right.data, view);
  // Side by side, a thin dark divider between them.
  const int w = left.width, h = left.height;
  face::Image pair(2 * w + kDividerWidth, h, kDividerGrey);
  const std::size_t row = 3u * static_cast<std::size_t>(w);
  for (int y = 0; y < h; ++y) {
    const std::size_t from = row * static_cast<std::size_t>(y);
    const std::size_t to = 3u * static_cast<std::size_t>(pair.width) * static_cast<std::size_t>(y);
    std::copy_n(left.rgb.begin() + from, row, pair.rgb.begin() + to);
    std::copy_n(right.rgb.begin() + from, row, pair.rgb.begin() + to + row + 3 * kDividerWidth);
  }

  char name[32];
  std::snprintf(name, sizeof name, "frames/frame_%05zu.png", s.frames.size());
  face::write_png((s.out_dir / name).string(), pair);
  s.frames.emplace_back(name);
  s.bytes += std::filesystem::file_size(s.out_dir / name);
  if (s.bytes > s.options.max_bytes) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "render: %zu frames take %.1f MB, above the %.1f MB that --max-output-mb leaves "
                  "them; raise it, or lower --duration",
                  s.frames.size(), static_cast<double>(s.bytes) / 1e6,
                  static_cast<double>(s.options.max_bytes) / 1e6);
    throw std::runtime_error(text);
  }
}

const std::vector<std::string>& RenderSequence::frames() const {
  return state_->frames;
}

}  // namespace facectl
