// The full layered face (thesis ch. 5) in the MuJoCo style: a FaceModel that is const
// after build_face_model(), and a FaceData workspace holding every mutable array, sized
// once by make_face_data(), so step_face() never allocates.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "control/face/mandible.hpp"
#include "facectl/face/constraints.hpp"
#include "facectl/face/convex_hull.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/muscle.hpp"
#include "facectl/face/skin_pins.hpp"

namespace facectl::face {

struct EyelidSide {
  Vec3 axis_point, axis;                // through the eyeball centre, parallel to the eye corners
  double upper_max = 0, lower_max = 0;  // rotation (rad) at closure 1, signed
};

struct FaceModel {
  HeadSpec spec;

  // Skin: the mesh (positions in m), inverse masses and its constraint network.
  TriMesh skin;
  std::vector<double> skin_w;
  DistanceConstraints skin_stretch;  // border edges; an interior edge's is in skin_pair_stretch
  BendingConstraints skin_bending;
  PairStretch skin_pair_stretch;  // stretch of skin_bending's shared edges, projected with it
  AreaConstraints skin_area;
  OrientationConstraints skin_upright;  // no-inversion (SkinStiffness::min_projected_area)
  Adjacency upright_of_vertex;          // vertex → its skin_upright constraints (CSR)
  VolumeConstraint skin_volume;
  // Skin anchors: vertex i follows the point carried in the frame of its support.
  std::vector<SurfacePoint> anchor_support;
  Points anchor_local;  // rest offset of vertex i in the support triangle's frame
  Attachments anchors;
  // The anchors by support: on a muscle, on the jaw (a skull triangle with a mandible
  // vertex), and on the rest of the skull, which never moves (targets set at reset).
  std::vector<int> anchors_on_muscles, anchors_on_jaw, anchors_on_fixed_skull;
  std::vector<double> influence;  // per skin vertex, in [0, 1]

  // Eyelids: particles driven rigidly by infinite-mass drivers.
  Attachments lids;
  std::vector<std::uint8_t> lid_side, lid_upper;
  std::vector<double> lid_profile;  // sin(π·s), s = position between the eye corners
  Points lid_rest;
  EyelidSide eyes[2];  // 0 = left (+x), 1 = right

  // Bones.
  TriMesh skull;                       // rest pose
  std::vector<int> mandible_vertices;  // skull vertices that move with the jaw
  MandibleAxes axes;
  ConvexHull upper_teeth, lower_teeth;  // rest pose

  // Muscles, deepest layer first. command_slot[m] is the index into the commanded
  // contractions, or −1 for a passive muscle.
  std::vector<Muscle> muscles;
  // Muscles of one layer rest only on lower layers and share no particle, so their single
  // iterations commute: the solver projects a layer's distance and bending constraints as
  // one set (batched across muscles, order_in_runs), then each muscle's volume and
  // attachments. Same result as muscle after muscle with those sets in that order.
  struct MuscleLayer {
    int first = 0, end = 0;  // muscles [first, end)
    DistanceConstraints distances;
    BendingConstraints bending;
  };
  std::vector<MuscleLayer> muscle_layers;
  std::vector<int> command_slot;
  std::vector<std::uint8_t> is_oculi;  // orbicularis oculi ring of side 0/1, else 2
  Points muscle_rest;
  std::vector<double> muscle_w;
  std::vector<Tri> muscle_tops;  // top surfaces of all muscles (skin supports)
  Points muscle_rest_normals;    // vertex normals of muscle_tops at rest

  // Landmarks on the skin: mean of vertices plus a fixed rest offset.
  std::vector<std::string> landmark_names;
  std::vector<std::vector<int>> landmark_vertices;
  std::vector<Vec3> landmark_offset;
  int landmark_index(const std::string& name) const;  // −1 if absent
  // landmark_index of each name, in order (the control points' landmarks).
  std::vector<int> landmark_indices(const std::vector<std::string>& names) const;
};

struct FaceInput {
  std::span<const double> contractions;  // head.yaml order, each in [0, 1]
  MandiblePose jaw;
  double eyelid_closure[2] = {0, 0};  // left, right in [0, 1]
  bool teeth_collision = true;
};

struct FaceData {
  Points skin_x, skin_prev, skin_p;
  Points skull;
  Points muscles, muscle_normals;
  Points muscles_before;  // the muscles at the start of the frame (under-relaxation)
  Points anchor_targets, lid_targets;
  Points grad;  // volume-gradient scratch, sized to the largest particle array
  MuscleScratch scratch;
  std::vector<double> contraction;  // per model muscle
  ConvexHull lower_teeth;
  RigidTransform jaw;
  // End-of-frame untangling (step_face): violated no-inversion constraints, marks.
  std::vector<int> untangle_list, untangle_next, vertex_mark, upright_mark;
  int untangle_stamp = 0;
  std::vector<int> hit_particle;  // teeth contacts of this frame
  Points hit_target;
  int hits = 0;
  long frame = 0;
  SkinPins pins;  // none unless set (skin_pins.hpp): vertices held like actuated points
};

// Builds the head from its spec. `skin_vertices` > base count selects a refined variant.
FaceModel build_face_model(const HeadSpec& spec, std::size_t skin_vertices = 0);
FaceData make_face_data(const FaceModel& m);
void reset_face_data(const FaceModel& m, FaceData& d);
// Constraint passes a frame: the skin's (0: the head's solver.skin_iterations) and the
// muscles'. Real-time runs keep the defaults. A steady-state solve may take more: every
// skin iteration ends as the head's one-iteration frame does, so a state one frame leaves
// unchanged is unchanged by more passes too, and more inputs reach the same settled
// states, in fewer frames (docs/FACE_MODEL.md, "Passes a frame for steady states").
struct SolverPasses {
  int skin = 0;
  int muscle = 1;
};

// One frame of §5.7: bones, muscles deepest first (one PBD iteration each per pass), skin
// anchors, teeth contacts, skin iterations, influence weights. Allocation-free.
void step_face(const FaceModel& m, FaceData& d, const FaceInput& in, SolverPasses passes = {});

// Steps (2)–(11) alone: bones, eyelid drivers and muscles (the thesis's "skull +
// muscles" row of Table 5.1). step_face() calls this first.
void step_skull_and_muscles(const FaceModel& m, FaceData& d, const FaceInput& in,
                            int muscle_passes = 1);

// The closure the lids of `side` (0 left, 1 right) take under `in`: its eyelid closure
// plus the palpebral orbicularis oculi's (AU 7) times the head's coupling, in [0, 1].
double lid_closure(const FaceModel& m, const FaceInput& in, int side);

Vec3 landmark_position(const FaceModel& m, const Points& skin, int landmark);
// A landmark of the spec on `skin` (base vertex numbering) without building the model:
// its vertices' mean plus its offset. Throws InputError for a vertex outside the skin.
Vec3 landmark_position(const LandmarkSpec& l, const Points& skin);
// The head's skin as face.yaml names it (metres), openings cut out: the model's base mesh.
TriMesh read_base_skin(const HeadSpec& spec);
// Counts skin vertices strictly inside a teeth hull (by `margin` m).
int skin_vertices_inside_teeth(const FaceModel& m, const FaceData& d, double margin);

}  // namespace facectl::face
