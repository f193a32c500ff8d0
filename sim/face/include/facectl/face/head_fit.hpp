// Placing a head's landmarks, openings and muscle map on a new skin mesh (issue 20,
// "Bringing your own head"; thesis §5.4 / chapter 6): the source head's skin is aligned
// to the target by bounding boxes, then bent onto it by the RBF morph G of rbf_morph.hpp,
// refitted from closest-point correspondences until they stop moving. Points on the skin
// are snapped to target vertices; bone points (landmarks with an offset, muscle corners)
// are carried by G and re-expressed as target landmark + offset.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "facectl/face/head_spec.hpp"
#include "facectl/face/mesh.hpp"
#include "facectl/face/rbf_morph.hpp"

namespace facectl::face {

struct HeadFitOptions {
  int max_iterations = 15;
  double converged_mm = 0.01;  // largest correspondence move between iterations
  int surface_samples = 60;    // source skin vertices added to the landmarks as correspondences
  // Source points closer than this to the rim of an opening the target has as a hole ride
  // with the rim (through G) instead of being projected (metres, source head).
  double rim_reach = 0.012;
  // Refinement: each round adds up to this many source vertices that G leaves farther than
  // refine_above_mm from the target surface.
  int worst_pairs = 25;
  double refine_above_mm = 0.5;
  // A skin landmark whose fitted point is farther than this many median target edge
  // lengths from the vertex it snapped to is reported as not placed.
  double max_snap_edges = 2.0;
};

struct PlacedLandmark {
  std::string name;
  bool bone = false;          // had an offset in the source: carried by G, not projected
  std::vector<int> vertices;  // target vertices (averaged)
  Vec3 offset = Vec3::Zero();
  Vec3 fitted = Vec3::Zero();  // G(source landmark): where it should be
  double initial_mm = 0;       // distance from the target surface after the initial alignment
  double snap_mm = 0;          // |placed − fitted|, placed = mean(vertices) + offset
};

struct HeadFit {
  RbfMorph morph;  // source rest positions → target, metres
  int iterations = 0;
  int refined_pairs = 0;     // correspondences the refinement added
  int last_added_pairs = 0;  // of which in the last round
  double last_change_mm = 0;
  // The correspondences stopped moving (by < converged_mm) and the refinement added none;
  // false: stopped at max_iterations.
  bool converged = false;
  std::vector<int> loose_vertices;  // target vertices used by no face: left out of the fit
  double size_ratio = 1;  // target / source face size (√ of width ratio × height ratio)
  // target / source skin area per vertex, over size_ratio²: how much coarser the new mesh
  // is for its size; the spec's skin stiffnesses are rescaled by it (skin_density.hpp)
  double vertex_area_ratio = 1;
  std::vector<PlacedLandmark> landmarks;
  std::vector<std::string> opening_notes;  // how each opening was found
  std::vector<std::string> problems;       // what could not be placed: errors
  HeadSpec spec;                           // the new head (skin_file/dir left for the writer)
};

// Throws InputError naming `what` when the mesh cannot be a face: too few vertices or
// triangles, degenerate (zero-area) triangles everywhere, a flat or empty bounding box,
// triangles referencing a vertex twice, an edge shared by more than two triangles
// (non-manifold; open borders are fine).
void check_head_mesh(const TriMesh& m, const std::string& what);
// The two halves of check_head_mesh: the mesh itself, and whether it covers a face
// looking along +z with y up (neither a whole head nor turned; find_face() can make it so).
void check_mesh_basics(const TriMesh& m, const std::string& what);
void check_face_region(const TriMesh& m, const std::string& what);

// How far m is from mirror-symmetric about the upright plane through its frontmost (+z)
// used vertex, that plane turned `turn` radians about y: the 90th percentile of the
// mirrored vertices' distances to the surface, over the mesh's width (x). 0 for the
// default head; a face looking along x gives over 0.1.
double mirror_asymmetry(const TriMesh& m, double turn);

// Vertices no triangle uses (ascending). fit_head leaves them out (never snaps to them);
// they keep their indices, so the mesh file stays valid as it is.
std::vector<int> loose_vertices(const TriMesh& m);

// `source_skin` is the source head's skin as read (openings not cut). Never throws for a
// fit that is poor: what it could not place goes to `problems`.
HeadFit fit_head(const HeadSpec& source, const TriMesh& source_skin, const TriMesh& target,
                 const HeadFitOptions& o);

// Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// The closest point to p on mesh m and the triangle it lies on (every triangle is tried:
// the meshes here have a few thousand). `triangle` is -1 for a mesh without triangles.
struct MeshPoint {
  Vec3 point;
  int triangle = -1;
};
MeshPoint closest_on_mesh(const TriMesh& m, const Vec3& p);

}  // namespace facectl::face
