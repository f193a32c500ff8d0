// The default head's files as data: face.yaml (model parameters), landmarks.yaml
// (MPEG-4 feature points on the skin mesh), muscles.yaml (the muscle map, placed by
// landmarks) and head.yaml (the commanded muscle order). Lengths here are metres;
// the YAML names its units (`_mm`, `units: cm`).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "facectl/face/muscle.hpp"
#include "facectl/face/points.hpp"

namespace facectl::face {

struct LandmarkSpec {
  std::string name;
  std::vector<int> vertices;  // skin vertices averaged
  Vec3 offset = Vec3::Zero();
  // Where its vertices are written, for errors found once the skin is read.
  std::string file;
  int line = 0, column = 0;  // 1-based
};

struct PointRef {
  std::string landmark;
  Vec3 offset = Vec3::Zero();
};

struct MuscleSpec {
  std::string name;
  MuscleKind kind = MuscleKind::kSheet;
  int layer = 0;
  int rows = 5, cols = 3;
  double thickness = 0.003;
  std::vector<PointRef> origin, insertion;  // sheet: two corners each
  std::vector<PointRef> inner, outer;       // sphincter: closed loops
};

struct SkinStiffness {
  double stretch = 0.15, bending = 0.95, area = 0.95, anchor = 0.2, volume = 1.0, damping = 0.2;
  // No-inversion constraint (not in the thesis, docs/FACE_MODEL.md): each triangle's area
  // projected on its rest normal stays ≥ this fraction of its rest area.
  double min_projected_area = 0.25;
};

struct HeadSpec {
  std::string dir;
  // The face's own files, relative to dir, in reading order: face.yaml, the skin, landmarks,
  // muscles. head.yaml (the control core's) is not among them; only its muscle order
  // shapes the face model.
  std::vector<std::string> files;
  std::string skin_file;
  double skin_scale = 0.01;
  std::vector<std::pair<std::string, std::vector<int>>> openings;
  std::vector<LandmarkSpec> landmarks;
  std::vector<MuscleSpec> muscles;
  std::vector<std::string> commanded, passive;  // from head.yaml
  std::vector<std::string> control_points;      // landmark names the reduced model reports
  double tissue_depth = 0.008;
  // Teeth: dental arches centred behind the stomion.
  double teeth_half_width = 0.022, teeth_depth = 0.03, teeth_height = 0.009, teeth_inset = 0.008,
         teeth_gap = 0.0005;
  // Eyelids (§5.5.1).
  double eyelid_band = 0.005, eyeball_radius = 0.012, upper_lid_share = 0.8,
         oculi_lid_coupling = 0.3;
  int skin_iterations = 1;
  double influence_falloff = 0.025;
  SkinStiffness skin;
  MuscleStiffness sheet, sphincter;
  std::vector<int> variants;  // skin vertex counts of the higher-resolution variants
};

// Loads <dir>/face.yaml and the files it names, plus <dir>/head.yaml. Throws InputError
// naming file:line:column, the key, what was expected and what was found.
HeadSpec load_head_spec(const std::string& dir);

// Metres per unit of a skin length unit: "m", "cm" or "mm" (face.yaml's `units`, fit-head's
// --units); 0 for any other name.
double metres_per_unit(const std::string& unit);

}  // namespace facectl::face
