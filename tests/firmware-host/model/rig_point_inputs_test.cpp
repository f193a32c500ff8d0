// The default rig's control-point channels read the reduced face model's inputs from the
// face signals the layout names: the muscles, the jaw and the eyelids (the lids sit after
// the eye signals in the layout, not next to the jaw as in the model's variables).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "control/face/reduced_face_model.hpp"
#include "control/mapping/rig_mapping.hpp"
#include "firmware-host/config/loaded_config.hpp"

namespace facectl {
namespace {

TEST(RigPointInputs, TheTickReadsEachInputFromItsOwnSignal) {
  const LoadedConfig cfg = load_config(default_config_path());
  const ControllerModel& m = cfg.built.model;
  const RigMapping& map = m.mapping;
  ASSERT_TRUE(map.reduced);
  const std::size_t n = m.layout.muscle_count();
  EXPECT_EQ(map.jaw_pitch, *m.layout.find("jaw_pitch"));
  EXPECT_EQ(map.eyelid_closure[0], *m.layout.find("eyelid_closure_l"));
  EXPECT_EQ(map.eyelid_closure[1], *m.layout.find("eyelid_closure_r"));

  // One input at a time away from rest: the tick's point rows against the dense rows over
  // the model evaluated on an input built from the named signal alone.
  MappingWorkspace w = make_mapping_workspace(map);
  face::ReducedFaceWorkspace full = face::make_reduced_workspace(*map.reduced);
  const std::vector<double> relaxed(n, 0.0);
  auto check = [&](const char* signal, double value, face::ReducedInput in) {
    std::array<double, kMaxFaceSignals> face{};
    face[*m.layout.find(signal)] = value;
    evaluate_control_points(map, w, face);
    face::evaluate_features(*map.reduced, full, in);
    const Eigen::VectorXd dense = map.projection.rows * full.features;
    double moved = 0;
    for (Eigen::Index r = 0; r < dense.size(); ++r) {
      EXPECT_NEAR(w.point_effector[static_cast<std::size_t>(r)], dense[r],
                  1e-12 * (1 + std::fabs(dense[r])))
          << signal << ", row " << r;
      moved = std::max(moved, std::fabs(dense[r]));
    }
    return moved;
  };
  face::ReducedInput lid_l{relaxed};
  lid_l.eyelid_closure[0] = 1.0;
  face::ReducedInput lid_r{relaxed};
  lid_r.eyelid_closure[1] = 1.0;
  // The brows move a little with their lid: the rows see it.
  EXPECT_GT(check("eyelid_closure_l", 1.0, lid_l), 0.0);
  EXPECT_GT(check("eyelid_closure_r", 1.0, lid_r), 0.0);
  face::ReducedInput open{relaxed, 0.2};
  EXPECT_GT(check("jaw_pitch", 0.2, open), 0.0);
}

}  // namespace
}  // namespace facectl
