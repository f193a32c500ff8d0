#include "expression_metrics.hpp"

#include <algorithm>

namespace facectl::face::testing {

ExpressionMetrics measure(const FaceModel& m, const Points& s) {
  auto now = [&](const char* n) -> Vec3 {
    return landmark_position(m, s, m.landmark_index(n)) * 1e3;
  };
  auto rest = [&](const char* n) -> Vec3 {
    return landmark_position(m, m.skin.v, m.landmark_index(n)) * 1e3;
  };
  auto d = [&](const char* n) -> Vec3 { return now(n) - rest(n); };
  ExpressionMetrics r{};
  r.corner_rise_l = d("fdp_8_3").y();
  r.corner_rise_r = d("fdp_8_4").y();
  r.corner_out_l = d("fdp_8_3").x();
  r.corner_out_r = -d("fdp_8_4").x();
  r.corner_back_l = -d("fdp_8_3").z();
  r.corner_back_r = -d("fdp_8_4").z();
  r.mouth_width =
      (now("fdp_8_3") - now("fdp_8_4")).norm() - (rest("fdp_8_3") - rest("fdp_8_4")).norm();
  r.lip_gap =
      (now("fdp_2_2").y() - now("fdp_2_3").y()) - (rest("fdp_2_2").y() - rest("fdp_2_3").y());
  r.upper_lip_rise = d("fdp_8_1").y();
  r.upper_lip_side_rise_l = d("fdp_8_5").y();
  r.upper_lip_side_rise_r = d("fdp_8_6").y();
  r.lip_protrusion = 0.5 * (d("fdp_8_1").z() + d("fdp_8_2").z());
  r.inner_brow_rise = 0.5 * (d("fdp_4_1").y() + d("fdp_4_2").y());
  r.outer_brow_rise = 0.5 * (d("fdp_4_5").y() + d("fdp_4_6").y());
  r.brow_rise = (d("fdp_4_1").y() + d("fdp_4_2").y() + d("fdp_4_3").y() + d("fdp_4_4").y() +
                 d("fdp_4_5").y() + d("fdp_4_6").y()) /
                6;
  r.inner_brow_gap =
      (now("fdp_4_1") - now("fdp_4_2")).norm() - (rest("fdp_4_1") - rest("fdp_4_2")).norm();
  r.chin_drop = -d("fdp_2_1").y();
  r.chin_shift = d("fdp_2_1").x();
  r.chin_forward = d("fdp_2_1").z();
  r.lower_lip_rise = d("fdp_8_2").y();
  r.nostril_rise = 0.5 * (d("fdp_9_1").y() + d("fdp_9_2").y());
  r.lid_ratio_l =
      (now("fdp_3_1").y() - now("fdp_3_3").y()) / (rest("fdp_3_1").y() - rest("fdp_3_3").y());
  r.lid_ratio_r =
      (now("fdp_3_2").y() - now("fdp_3_4").y()) / (rest("fdp_3_2").y() - rest("fdp_3_4").y());
  for (std::size_t i = 0; i < s.size(); ++i)
    r.max_skin = std::max(r.max_skin, (s.get(i) - m.skin.v.get(i)).norm() * 1e3);
  return r;
}

}  // namespace facectl::face::testing
