#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"

namespace facectl {

struct RenderOptions {
  double fps = 25;
  int width = 400;
  int height = 400;
  // add_frame throws once the frames written take more (simulate's
  // --max-output-mb, less what the rest of its outputs may take).
  std::uint64_t max_bytes = UINT64_MAX;
};

// The face render sequence of `facectl simulate --render` (docs/SIMULATE.md,
// "Render frames"): per frame, two views side by side. Left: the full face
// model for the commanded face. Right: the full face model for the face that
// the simulated actuator positions give back through the inverse of the rig's
// mapping, i.e. what the actuated head would do.
class RenderSequence {
 public:
  RenderSequence(const LoadedConfig& config, const std::filesystem::path& out_dir,
                 RenderOptions options = {});
  ~RenderSequence();
  RenderSequence(const RenderSequence&) = delete;
  RenderSequence& operator=(const RenderSequence&) = delete;

  // face_values: the face command given to the controller (SI, layout order,
  // as OfflineHead::send takes it); positions: simulated actuator positions
  // (actuator order, SI). Writes out_dir/frames/frame_NNNNN.png; throws
  // std::runtime_error if the frames now exceed options.max_bytes.
  void add_frame(std::span<const double> face_values, std::span<const double> positions);
  const std::vector<std::string>& frames() const;  // paths relative to out_dir

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace facectl
