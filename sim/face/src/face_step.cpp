// One frame of the layered solver, in the order of thesis §5.7.
#include <algorithm>
#include <cmath>
#include <utility>

#include "facectl/face/face_model.hpp"
#include "skin_anchors.hpp"

namespace facectl::face {
namespace {

void update_bones(const FaceModel& m, FaceData& d, const MandiblePose& pose) {
  d.jaw = mandible_transform(m.axes, pose);
  for (int v : m.mandible_vertices) d.skull.set(v, d.jaw.apply(m.skull.v.get(v)));
  transform_hull(m.lower_teeth, d.jaw, d.lower_teeth);
}

void update_lid_drivers(const FaceModel& m, FaceData& d, const double closure[2]) {
  for (std::size_t j = 0; j < m.lids.size(); ++j) {
    const EyelidSide& e = m.eyes[m.lid_side[j]];
    const double a =
        closure[m.lid_side[j]] * m.lid_profile[j] * (m.lid_upper[j] ? e.upper_max : e.lower_max);
    d.lid_targets.set(j, rotation_about_line(e.axis_point, e.axis, a).apply(m.lid_rest.get(j)));
  }
}

// Layer by layer, deepest first; within a layer the muscles' one iteration each, with
// their distance and bending sets projected together (FaceModel::MuscleLayer). The frame's
// muscle update F is then under-relaxed, x ← x + ω·(F(x) − x): the same fixed points, but
// each eigenvalue λ of the iteration becomes 1 − ω + ω·λ. The sphincters and some
// corrugators sat in period-2 cycles (λ ≈ −1: the k = 1 distance and volume projections
// overshooting against the attachments' pull); ω = 3/4 makes that −1/2, and slows the slow modes (λ
// near 1) by only a quarter where ω = 1/2 would halve their speed (docs/FACE_MODEL.md, "Steady
// state").
constexpr double kMuscleRelaxation = 0.75;

void step_muscles(const FaceModel& m, FaceData& d) {
  Points& x = d.muscles;
  Points& before = d.muscles_before;
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i)
    before.x[i] = x.x[i], before.y[i] = x.y[i], before.z[i] = x.z[i];
  for (const FaceModel::MuscleLayer& L : m.muscle_layers) {
    project(L.distances, x, m.muscle_w);
    project(L.bending, x, m.muscle_w);
    for (int k = L.first; k < L.end; ++k)
      finish_muscle_step(m.muscles[k], d.contraction[k], d.skull, x, m.muscle_w, d.scratch, d.grad);
  }
  for (std::size_t i = 0; i < n; ++i) {
    x.x[i] = before.x[i] + kMuscleRelaxation * (x.x[i] - before.x[i]);
    x.y[i] = before.y[i] + kMuscleRelaxation * (x.y[i] - before.y[i]);
    x.z[i] = before.z[i] + kMuscleRelaxation * (x.z[i] - before.z[i]);
  }
}

// Contact response against one hull: a position constraint to where the ray from p
// leaves the hull, along ±dir whichever is nearer.
bool contact(const ConvexHull& h, const Vec3& p, const Vec3& dir, Vec3& target) {
  if (!inside(h, p)) return false;
  const double up = exit_distance(h, p, dir), down = exit_distance(h, p, -dir);
  target = up <= down ? Vec3(p + up * dir) : Vec3(p - down * dir);
  return true;
}

void detect_teeth(const FaceModel& m, FaceData& d, const Points& p) {
  d.hits = 0;
  const Vec3 vertical = m.axes.yaw_axis;                     // sagittal ∩ coronal plane
  const Vec3 forward = d.jaw.rotate(m.axes.protrusion_dir);  // the jaw's protrusion direction
  // Broad phase over both hulls' boxes, on the raw arrays: almost every skin vertex is far
  // from the teeth, and inside() would reject it by the same boxes, only slower.
  const Vec3 lo = m.upper_teeth.box_min.cwiseMin(d.lower_teeth.box_min);
  const Vec3 hi = m.upper_teeth.box_max.cwiseMax(d.lower_teeth.box_max);
  for (std::size_t i = 0; i < p.size(); ++i) {
    // Bitwise on purpose (no branch per test); int operands say so to clang.
    if (int{p.x[i] < lo.x()} | int{p.x[i] > hi.x()} | int{p.y[i] < lo.y()} | int{p.y[i] > hi.y()} |
        int{p.z[i] < lo.z()} | int{p.z[i] > hi.z()})
      continue;
    const Vec3 q = p.get(i);
    Vec3 t;
    if (contact(m.upper_teeth, q, vertical, t) || contact(d.lower_teeth, q, forward, t)) {
      d.hit_particle[d.hits] = static_cast<int>(i);
      d.hit_target.set(d.hits, t);
      ++d.hits;
    }
  }
}

// Gauss–Seidel on the violated no-inversion constraints alone, until none is violated (at
// most kUntangleRounds rounds): each round projects the list in index order, then lists
// the violated constraints next to a vertex it moved. A constraint counts as violated
// below 0.9 times its bound and is projected onto the bound. The 10% between keeps the
// rounds few (with both at the bound, neighbours ping-pong for hundreds of rounds: 3
// times the step time at 4904 vertices); projecting onto 1.5 times the bound instead
// made the frame map jump by half a bound and the mouth corners cycle by up to 1.4 mm a
// frame forever (docs/FACE_MODEL.md, "Steady state"). Usually empty; where the anchors
// fold the skin (the mouth corners) a few hundred constraints need it. Deterministic and
// allocation-free.
void untangle(const FaceModel& m, FaceData& d, Points& p) {
  constexpr int kUntangleRounds = 256;
  constexpr double kUntangleFloor = 0.9, kUntangleTarget = 1.0;
  const OrientationConstraints& o = m.skin_upright;
  int* list = d.untangle_list.data();  // both sized to o.size(): no allocation
  int* next = d.untangle_next.data();
  int n = 0;
  for (std::size_t i = 0; i < o.size(); ++i)
    if (orientation_value(o, i, p, kUntangleFloor) < 0) list[n++] = static_cast<int>(i);
  for (int round = 0; round < kUntangleRounds && n > 0; ++round) {
    const int id = ++d.untangle_stamp;  // never reset, so marks of earlier frames never match
    for (int j = 0; j < n; ++j) {
      const int i = list[j];
      if (project_one(o, static_cast<std::size_t>(i), p, m.skin_w, kUntangleFloor, kUntangleTarget))
        for (int v : {o.a[i], o.b[i], o.c[i]}) d.vertex_mark[v] = id;
    }
    int nn = 0;
    for (int j = 0; j < n; ++j) {
      const int i = list[j];
      for (int v : {o.a[i], o.b[i], o.c[i]}) {
        if (d.vertex_mark[v] != id) continue;
        for (int k = m.upright_of_vertex.start[v]; k < m.upright_of_vertex.start[v + 1]; ++k) {
          const int c = m.upright_of_vertex.nbr[k];
          if (d.upright_mark[c] == id) continue;
          d.upright_mark[c] = id;  // each constraint is listed at most once a round
          if (orientation_value(o, static_cast<std::size_t>(c), p, kUntangleFloor) < 0)
            next[nn++] = c;
        }
      }
    }
    std::sort(next, next + nn);
    std::swap(list, next);
    n = nn;
  }
}

void project_contacts(FaceData& d, Points& p) {
  for (int j = 0; j < d.hits; ++j) p.set(d.hit_particle[j], d.hit_target.get(j));
}

// The skin iterations (15), each ended by the influence weighting (16)–(17), the eyelid
// drivers and the untangling. With one iteration, the head's default, this is the
// thesis's frame. Ending each of several iterations the same way (SolverPasses) keeps
// the head's steady states: run once after all of them, those steps settled dense mixes
// 0.2–0.3 mm away from the head's (docs/FACE_MODEL.md, "Passes a frame for steady
// states"). Each interior edge's stretch rides with its bending pair ("Fused edge sweep").
void iterate_skin(const FaceModel& m, FaceData& d, Points& p, int iterations) {
  const Points& x = d.skin_x;
  const std::size_t ns = x.size();
  for (int it = 0; it < iterations; ++it) {
    project(m.skin_stretch, p, m.skin_w);  // border edges
    project_with_stretch(m.skin_bending, m.skin_pair_stretch, p, m.skin_w);
    project(m.skin_area, p, m.skin_w);
    project(m.skin_volume, p, m.skin_w, d.grad);
    project(m.anchors, p, m.skin_w, d.anchor_targets);
    project(m.skin_upright, p, m.skin_w);  // after the anchors, which fold the surface
    project(m.lids, p, m.skin_w, d.lid_targets);
    project_contacts(d, p);
    apply_skin_pins(d.pins, p);
    // A vertex moves by its influence's share of the way from where the frame found it;
    // eyelid particles keep their drivers' motion.
    for (std::size_t i = 0; i < ns; ++i) {
      const double w = m.influence[i];
      p.x[i] = x.x[i] + w * (p.x[i] - x.x[i]);
      p.y[i] = x.y[i] + w * (p.y[i] - x.y[i]);
      p.z[i] = x.z[i] + w * (p.z[i] - x.z[i]);
    }
    for (std::size_t j = 0; j < m.lids.size(); ++j) p.set(m.lids.particle[j], d.lid_targets.get(j));
    untangle(m, d, p);
    apply_skin_pins(d.pins, p);  // the weighting and untangling moved them off
  }
}

}  // namespace

double lid_closure(const FaceModel& m, const FaceInput& in, int side) {
  // The palpebral part of the orbicularis oculi narrows the eye (AU 7). One muscle per side
  // at most: it is found by name, and build_face_model refuses two muscles of one name.
  double oculi = 0;
  for (std::size_t k = 0; k < m.muscles.size(); ++k) {
    const int slot = m.command_slot[k];
    if (m.is_oculi[k] == side && slot >= 0 &&
        static_cast<std::size_t>(slot) < in.contractions.size())
      oculi = std::clamp(in.contractions[static_cast<std::size_t>(slot)], 0.0, 1.0);
  }
  return std::clamp(in.eyelid_closure[side] + m.spec.oculi_lid_coupling * oculi, 0.0, 1.0);
}

void step_skull_and_muscles(const FaceModel& m, FaceData& d, const FaceInput& in,
                            int muscle_passes) {
  // (2)–(7) inputs and rigid parts.
  for (std::size_t k = 0; k < m.muscles.size(); ++k) {
    const int slot = m.command_slot[k];
    d.contraction[k] = slot >= 0 && static_cast<std::size_t>(slot) < in.contractions.size()
                           ? std::clamp(in.contractions[slot], 0.0, 1.0)
                           : 0.0;
  }
  const double closure[2] = {lid_closure(m, in, 0), lid_closure(m, in, 1)};
  update_bones(m, d, in.jaw);
  update_lid_drivers(m, d, closure);
  // (8)–(11) muscles, deepest first.
  for (int k = 0; k < muscle_passes; ++k) step_muscles(m, d);
}

void step_face(const FaceModel& m, FaceData& d, const FaceInput& in, SolverPasses passes) {
  step_skull_and_muscles(m, d, in, passes.muscle);
  // (12)–(13) skin anchors.
  update_moving_anchor_targets(m, d);
  // Prediction with damping: v ← (1 − damping)·v, p = x + v·Δt (Δt cancels, see §2).
  const double keep = 1 - m.spec.skin.damping;
  Points& x = d.skin_x;
  Points& p = d.skin_p;
  const std::size_t ns = x.size();
  for (std::size_t i = 0; i < ns; ++i) {
    p.x[i] = x.x[i] + keep * (x.x[i] - d.skin_prev.x[i]);
    p.y[i] = x.y[i] + keep * (x.y[i] - d.skin_prev.y[i]);
    p.z[i] = x.z[i] + keep * (x.z[i] - d.skin_prev.z[i]);
  }
  // (14) teeth contacts, (15)–(17) skin iterations with the contacts included, each
  // weighted by the influence map.
  if (in.teeth_collision)
    detect_teeth(m, d, p);
  else
    d.hits = 0;
  iterate_skin(m, d, p, passes.skin > 0 ? passes.skin : m.spec.skin_iterations);
  // The weighting can move a contact back inside; re-detect so no vertex ends inside.
  if (in.teeth_collision) {
    detect_teeth(m, d, p);
    project_contacts(d, p);
  }
  std::swap(d.skin_prev, d.skin_x);  // prev ← x
  std::swap(d.skin_x, d.skin_p);     // x ← p
  ++d.frame;
}

int skin_vertices_inside_teeth(const FaceModel& m, const FaceData& d, double margin) {
  int n = 0;
  for (std::size_t i = 0; i < d.skin_x.size(); ++i) {
    const Vec3 q = d.skin_x.get(i);
    n += inside(m.upper_teeth, q, -margin) || inside(d.lower_teeth, q, -margin);
  }
  return n;
}

}  // namespace facectl::face
