#include "firmware-host/cli/clone_head_ranges.hpp"

#include "firmware-host/config/head_config.hpp"

namespace facectl {

void set_head_ranges(const face::HeadSpec& head, face::MotionCloneOptions& o) {
  const HeadConfig config = load_head_config(head.dir + "/head.yaml");
  o.jaw = face::design_jaw_bounds();
  if (config.envelope) {
    const EnvelopeSpec& e = *config.envelope;
    if (e.pitch) o.jaw.pitch_min = e.pitch->min, o.jaw.pitch_max = e.pitch->max;
    if (e.yaw) o.jaw.yaw_min = e.yaw->min, o.jaw.yaw_max = e.yaw->max;
    if (e.protrusion)
      o.jaw.protrusion_min = e.protrusion->min, o.jaw.protrusion_max = e.protrusion->max;
  }
  for (int side = 0; side < 2; ++side) {
    const auto r = config.rigid_ranges.find(side == 0 ? "eyelid_closure_l" : "eyelid_closure_r");
    o.eyelid[side] = r == config.rigid_ranges.end() ? face::LidRange{}
                                                    : face::LidRange{r->second.min, r->second.max};
  }
}

}  // namespace facectl
