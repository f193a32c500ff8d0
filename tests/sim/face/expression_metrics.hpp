// Geometric measures of an expression on the simulated skin, in mm, against the rest
// face: the quantities the Faigin descriptions talk about (corners, brows, lips, lids).
#pragma once

#include "facectl/face/face_model.hpp"

namespace facectl::face::testing {

struct ExpressionMetrics {
  double corner_rise_l, corner_rise_r;                  // 8.3 / 8.4 Δy
  double corner_out_l, corner_out_r;                    // 8.3 +Δx, 8.4 −Δx (outward)
  double corner_back_l, corner_back_r;                  // −Δz (toward the ears)
  double mouth_width;                                   // Δ|8.3 − 8.4|
  double lip_gap;                                       // Δ(2.2.y − 2.3.y)
  double upper_lip_rise;                                // 8.1 Δy
  double upper_lip_side_rise_l, upper_lip_side_rise_r;  // 8.5 / 8.6 Δy
  double lip_protrusion;                                // mean Δz of 8.1, 8.2
  double inner_brow_rise, outer_brow_rise, brow_rise;   // mean Δy of 4.1/4.2, 4.5/4.6, all six
  double inner_brow_gap;                                // Δ|4.1 − 4.2|
  double chin_drop;                                     // −Δy of 2.1
  double chin_shift;                                    // Δx of 2.1
  double chin_forward;                                  // Δz of 2.1
  double lower_lip_rise;                                // 8.2 Δy
  double nostril_rise;                                  // mean Δy of 9.1, 9.2
  double lid_ratio_l, lid_ratio_r;                      // lid gap (3.1–3.3) / rest gap
  double max_skin;                                      // largest skin vertex displacement
};

ExpressionMetrics measure(const FaceModel& m, const Points& skin);

}  // namespace facectl::face::testing
