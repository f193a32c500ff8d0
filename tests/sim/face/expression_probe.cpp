// Development aid (not a test): prints the acceptance measures of every expression at its
// steady state (as expression_test.cpp), or after FRAMES frames if given.
#include <cstdio>

#include "expression_metrics.hpp"
#include "facectl/face/expression_library.hpp"
#include "facectl/face/steady_state.hpp"

using namespace facectl::face;

int main(int argc, char** argv) {
  const HeadSpec spec = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  const FaceModel m = build_face_model(spec);
  const ExpressionLibrary lib =
      load_expression_library(FACECTL_CONFIG_DIR "/expressions/library.yaml", spec);
  FaceData d = make_face_data(m);
  const int frames = argc > 1 ? std::atoi(argv[1]) : 0;
  std::printf(
      "%-17s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s %5s\n",
      "expr", "crL", "crR", "coL", "coR", "cbL", "cbR", "mw", "gap", "ulip", "prot", "ibr", "obr",
      "br", "ibg", "chin", "chx", "lidL", "lidR", "ulsL", "ulsR");
  for (const Expression& e : lib.expressions) {
    if (frames > 0) {
      simulate_expression(m, d, e, frames);
    } else {
      reset_face_data(m, d);
      run_to_steady_state(m, d, face_input(e), SteadyStateOptions{});
    }
    auto r = testing::measure(m, d.skin_x);
    std::printf(
        "%-17s %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f %5.1f "
        "%5.1f %5.1f %5.2f %5.2f %5.1f %5.1f\n",
        e.name.c_str(), r.corner_rise_l, r.corner_rise_r, r.corner_out_l, r.corner_out_r,
        r.corner_back_l, r.corner_back_r, r.mouth_width, r.lip_gap, r.upper_lip_rise,
        r.lip_protrusion, r.inner_brow_rise, r.outer_brow_rise, r.brow_rise, r.inner_brow_gap,
        r.chin_drop, r.chin_shift, r.lid_ratio_l, r.lid_ratio_r, r.upper_lip_side_rise_l,
        r.upper_lip_side_rise_r);
  }
}
