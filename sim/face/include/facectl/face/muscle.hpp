// One muscle of thesis ch. 4: a closed box mesh (bottom grid rows × cols and top grid
// offset by the thickness) with its own constraint network, driven by action lines
// made of surface points on the layers beneath it.
//
// Sheet muscle: every column c has its own fibre action line from origin to insertion
// (A0 is column 0, A2 column cols−1, the rest are the thesis's extra internal lines for
// wide muscles). Row r of the bottom grid follows the sample at arc length
// r·step·(1 − c_contraction) measured from the origin end on every fibre (eq. 4.11 with
// errata 4 and 8: step = L/(rows−1)).
//
// Sphincter (rows = 2): row 0 follows the inner closed action line A1, row 1 the outer
// A3, each resampled at cols points; contraction moves each pair toward the centre by
// δ = (o − s1)·c·cos(π/2·(1 − √(x²b² + y²a²)/(ab))) (§4.3.2 with erratum 9 and the
// 1/w of erratum 10). The two rings are stored in the same angular order, so sample i of
// A1 pairs with sample i of A3 (the thesis's j = w−1−i for its opposite-running lines).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "facectl/face/constraints.hpp"
#include "facectl/face/surface_point.hpp"

namespace facectl::face {

enum class MuscleKind { kSheet, kSphincter };

struct MuscleStiffness {
  double up_latitudinal = 0, up_longitudinal = 0, low_latitudinal = 0, low_longitudinal = 0;
  double connection = 0, up_shear = 0, low_shear = 0, bend = 0, volume = 0, position = 0;
};

struct Muscle {
  std::string name;
  MuscleKind kind = MuscleKind::kSheet;
  int layer = 0;
  int rows = 0, cols = 0;
  int first = 0;  // index of this muscle's first particle in the shared muscle arrays
  // Sheet: `cols` fibre polylines (origin → insertion). Sphincter: 2 closed polylines
  // (inner, outer).
  std::vector<std::vector<SurfacePoint>> lines;
  std::vector<Tri> surface;  // closed box surface, outward, global particle indices
  DistanceConstraints distances;
  BendingConstraints bending;
  VolumeConstraint volume;
  Attachments attach;  // bottom particle r*cols + c follows target r*cols + c
  int particle_count() const { return 2 * rows * cols; }
};

// Per-muscle scratch, preallocated by the builder.
struct MuscleScratch {
  Points line_pos;  // polyline points of one line
  std::vector<double> arc;
  Points column;   // the samples of one fibre
  Points targets;  // rows*cols attachment goals
};

// Appends the muscle's rest particles to `pos` (bottom grid on the rest samples of its
// lines, top grid `thickness` along normal_at(p)), sets m.first, builds its constraints.
void place_muscle(Muscle& m, double thickness, const std::function<Vec3(const Vec3&)>& normal_at,
                  const Points& skull, Points& pos, const MuscleStiffness& k);
// One PBD iteration of one muscle at contraction c (thesis): attachment goals from
// the current supports, then distances, bending, volume and attachments in that order.
void step_muscle(const Muscle& m, double c, const Points& skull, Points& pos,
                 const std::vector<double>& w, MuscleScratch& s, Points& grad);
// The rest of step_muscle() after its distance and bending projections: attachment goals,
// volume, attachments (the face solver projects a layer's distances and bending at once).
void finish_muscle_step(const Muscle& m, double c, const Points& skull, Points& pos,
                        const std::vector<double>& w, MuscleScratch& s, Points& grad);
// Scratch sized for muscle m (the builder sizes one for the largest muscle).
MuscleScratch make_muscle_scratch(std::size_t max_line, std::size_t max_grid);
// Builds the box mesh and constraints for particles already placed in `pos` at
// [m.first, m.first + 2·rows·cols): bottom grid first, then top grid.
void build_muscle_constraints(Muscle& m, const Points& pos, const MuscleStiffness& k);
// Computes the attachment goals for contraction c from the current support layers.
void muscle_targets(const Muscle& m, double c, const Points& skull, const Points& muscles,
                    MuscleScratch& s);
// The share of its line a sheet's rows are sampled over at contraction c: the thesis's
// 1 − c up to kSheetKnee, then a parabola with the same slope there that ends flat at
// kSheetShortest for c = 1. At 1 − c = 0 every row's target is the line's origin, which
// fibres of their rest lengths cannot reach: 16 of 29 muscles alone at c = 1 never
// settled (docs/FACE_MODEL.md, "Muscles alone near full contraction").
constexpr double kSheetKnee = 0.9, kSheetShortest = 0.05;
double sheet_length_scale(double c);
// Samples `n` points at arc length i·step·scale (open) or evenly around a closed loop.
void sample_polyline(const Points& poly, std::vector<double>& arc, bool closed, int n, double scale,
                     Points& out, int out_offset);

}  // namespace facectl::face
