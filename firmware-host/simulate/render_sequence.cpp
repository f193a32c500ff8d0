#include "firmware-host/simulate/render_sequence.hpp"

namespace facectl {

// Stub so that the simulate command can compile against the interface; the
// renderer follows.
struct RenderSequence::State {
  std::filesystem::path out_dir;
  RenderOptions options;
  std::vector<std::string> frames;
};

RenderSequence::RenderSequence(const LoadedConfig&, const std::filesystem::path& out_dir,
                               RenderOptions options)
    : state_(std::make_unique<State>(State{out_dir, options, {}})) {}

RenderSequence::~RenderSequence() = default;

void RenderSequence::add_frame(std::span<const double>, std::span<const double>) {}

const std::vector<std::string>& RenderSequence::frames() const {
  return state_->frames;
}

}  // namespace facectl
