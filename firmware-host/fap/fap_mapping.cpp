#include "firmware-host/fap/fap_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "control/units.hpp"
#include "facectl/face/input_error.hpp"

namespace facectl {
namespace {

face::Vec3 direction_vector(FapDirection d) {
  switch (d) {
    case FapDirection::kUp:
      return {0, 1, 0};
    case FapDirection::kDown:
      return {0, -1, 0};
    case FapDirection::kLeft:
      return {1, 0, 0};
    case FapDirection::kRight:
      return {-1, 0, 0};
    case FapDirection::kForward:
      return {0, 0, 1};
    default:
      return {0, 0, 0};
  }
}

// The rotation angle about the line (p, unit a) that moves point c by `target`
// along unit e, the root nearest 0. With r the part of c - p normal to a, the
// displacement along e is A (cos t - 1) + B sin t, A = e.r, B = e.(a x r).
double rotation_for_displacement(const face::Vec3& c, const face::Vec3& p, const face::Vec3& a,
                                 const face::Vec3& e, double target, bool* reachable) {
  const face::Vec3 r = (c - p) - a * a.dot(c - p);
  const double A = e.dot(r);
  const double B = e.dot(a.cross(r));
  const double R = std::hypot(A, B);
  double k = (A + target) / R;
  if (reachable) *reachable = std::abs(k) <= 1.0;
  k = std::clamp(k, -1.0, 1.0);
  const double phi = std::atan2(B, A);
  const double delta = std::acos(k);
  auto wrap = [](double t) { return std::remainder(t, 2.0 * kPi); };
  const double t1 = wrap(phi + delta), t2 = wrap(phi - delta);
  return std::abs(t1) <= std::abs(t2) ? t1 : t2;
}

struct MuscleRouteSpec {
  int fap;
  const char* point;  // control point of the reduced model standing for the FAP's FDP
  std::vector<const char*> positive, negative;
};

// Which muscles move each FAP's feature point, for positive and negative
// values, chosen from what the reduced face model says each muscle moves
// (docs/FAP.md). Where the model has no control point at the FAP's FDP the
// nearest one stands in.
const std::vector<MuscleRouteSpec>& muscle_route_specs() {
  const std::vector<const char*> lls = {"levator_labii_superioris_l", "levator_labii_superioris_r"};
  const std::vector<const char*> dli = {"depressor_labii_inferioris_l",
                                        "depressor_labii_inferioris_r"};
  static const std::vector<MuscleRouteSpec> specs = {
      {4, "fdp_2_2", {"orbicularis_oris"}, lls},
      {5, "fdp_8_2", {"orbicularis_oris"}, dli},
      {6, "fdp_8_3", {"risorius_l"}, {"orbicularis_oris"}},
      {7, "fdp_8_4", {"risorius_r"}, {"orbicularis_oris"}},
      {8, "fdp_2_2", {"orbicularis_oris"}, {"levator_labii_superioris_l"}},
      {9, "fdp_2_2", {"orbicularis_oris"}, {"levator_labii_superioris_r"}},
      {10, "fdp_8_2", {"orbicularis_oris"}, {"depressor_labii_inferioris_l"}},
      {11, "fdp_8_2", {"orbicularis_oris"}, {"depressor_labii_inferioris_r"}},
      {12, "fdp_8_3", {"zygomaticus_major_l"}, {"depressor_anguli_oris_l"}},
      {13, "fdp_8_4", {"zygomaticus_major_r"}, {"depressor_anguli_oris_r"}},
      {16, "fdp_8_2", {"orbicularis_oris"}, {}},
      {17, "fdp_8_1", {"orbicularis_oris"}, {}},
      {31, "fdp_4_1", {"frontalis_inner_l"}, {"procerus_l"}},
      {32, "fdp_4_2", {"frontalis_inner_r"}, {"procerus_r"}},
      {33, "fdp_4_3", {"frontalis_l"}, {"corrugator_supercilii_l"}},
      {34, "fdp_4_4", {"frontalis_r"}, {"corrugator_supercilii_r"}},
      {35, "fdp_4_5", {"frontalis_outer_l"}, {}},
      {36, "fdp_4_6", {"frontalis_outer_r"}, {}},
      {37, "fdp_4_1", {"corrugator_supercilii_l"}, {}},
      {38, "fdp_4_2", {"corrugator_supercilii_r"}, {}},
      {41, "fdp_5_1", {"zygomaticus_major_l"}, {}},
      {42, "fdp_5_2", {"zygomaticus_major_r"}, {}},
      {51, "fdp_8_1", {"orbicularis_oris"}, lls},
      {52, "fdp_8_2", {"orbicularis_oris"}, dli},
      {53, "fdp_8_3", {"risorius_l"}, {"orbicularis_oris"}},
      {54, "fdp_8_4", {"risorius_r"}, {"orbicularis_oris"}},
      {55, "fdp_8_1", {"orbicularis_oris"}, {"levator_labii_superioris_l"}},
      {56, "fdp_8_1", {"orbicularis_oris"}, {"levator_labii_superioris_r"}},
      {57, "fdp_8_2", {"orbicularis_oris"}, {"depressor_labii_inferioris_l"}},
      {58, "fdp_8_2", {"orbicularis_oris"}, {"depressor_labii_inferioris_r"}},
      {59, "fdp_8_3", {"zygomaticus_major_l"}, {"depressor_anguli_oris_l"}},
      {60, "fdp_8_4", {"zygomaticus_major_r"}, {"depressor_anguli_oris_r"}},
      {63,
       "fdp_9_1",
       {"levator_labii_superioris_alaeque_nasi_l", "levator_labii_superioris_alaeque_nasi_r"},
       {}},
  };
  return specs;
}

constexpr const char* kExpressionNames[7] = {"",     "joy",     "sadness", "anger",
                                             "fear", "disgust", "surprise"};

std::string format_value(double si, const std::string& unit) {
  char buf[64];
  if (unit == "deg") {
    std::snprintf(buf, sizeof buf, "%.3f deg", si / kDeg);
  } else if (unit == "mm") {
    std::snprintf(buf, sizeof buf, "%.3f mm", si * 1e3);
  } else if (unit.empty()) {
    std::snprintf(buf, sizeof buf, "%.4f", si);
  } else {
    std::snprintf(buf, sizeof buf, "%.6g %s", si, unit.c_str());
  }
  return buf;
}

std::string unit_of(const SignalInfo& info) {
  return std::string(yaml_unit(info.kind));
}

}  // namespace

void FapState::apply(const FapFrame& frame) {
  for (std::size_t i = 0; i < kFapCount; ++i) {
    if (frame.mask[i]) values[i] = frame.values[i];
  }
  if (frame.mask[0]) viseme = frame.viseme;
  if (frame.mask[1]) expression = frame.expression;
}

std::string describe(const FapClamp& c) {
  std::string who = "FAP " + std::to_string(c.fap) + " " + std::string(fap_info(c.fap).name);
  const double by = c.requested - c.applied;
  return "frame " + std::to_string(c.frame) + ", " + who + ": " + c.signal + " " +
         format_value(c.requested, c.unit) + " clamped to " + format_value(c.applied, c.unit) +
         " (by " + format_value(std::abs(by), c.unit) + ")";
}

FapMapping FapMapping::build(const HeadConfig& head, const FeaturePoints& points,
                             const face::ReducedFaceModel& reduced,
                             const ExpressionLibrary& expressions, const VisemeTable& visemes) {
  FapMapping m;
  m.layout_ = head.layout;
  m.fapu_ = compute_fapu(points);
  m.neutral_ = head.neutral;
  m.axes_ = face::mandible_axes(points.at("fdp_2_13"), points.at("fdp_2_14"), points.at("fdp_11_4"),
                                points.at("fdp_7_1"), points.at("fdp_2_10"));
  m.chin_ = points.at("fdp_2_1");

  // The envelope: design defaults narrowed (or, with the override, widened) by the head.
  m.envelope_ = MandibleEnvelope::design_default();
  if (head.envelope) {
    if (head.envelope->pitch) m.envelope_.pitch = *head.envelope->pitch;
    if (head.envelope->yaw) m.envelope_.yaw = *head.envelope->yaw;
    if (head.envelope->protrusion) m.envelope_.protrusion = *head.envelope->protrusion;
  }
  const FaceLayout& L = m.layout_;
  for (std::size_t i = 0; i < L.size(); ++i) {
    m.lo_[i] = L.signal(i).domain_min;
    m.hi_[i] = L.signal(i).domain_max;
    const auto r = head.rigid_ranges.find(L.signal(i).name);
    if (r != head.rigid_ranges.end()) {
      m.lo_[i] = r->second.min;
      m.hi_[i] = r->second.max;
    }
  }
  m.lo_[L.jaw_pitch()] = m.envelope_.pitch.min;
  m.hi_[L.jaw_pitch()] = m.envelope_.pitch.max;
  m.lo_[L.jaw_yaw()] = m.envelope_.yaw.min;
  m.hi_[L.jaw_yaw()] = m.envelope_.yaw.max;
  m.lo_[L.jaw_protrusion()] = m.envelope_.protrusion.min;
  m.hi_[L.jaw_protrusion()] = m.envelope_.protrusion.max;

  auto signal = [&](std::string_view name) {
    const auto i = L.find(name);
    if (!i)
      throw ConfigError(head.file + ": the FAP mapping needs face signal '" + std::string(name) +
                        "', which this head lacks");
    return *i;
  };
  m.eyelid_l_ = signal("eyelid_closure_l");
  m.eyelid_r_ = signal("eyelid_closure_r");
  m.eye_yaw_l_ = signal("eye_yaw_l");
  m.eye_yaw_r_ = signal("eye_yaw_r");
  m.eye_pitch_l_ = signal("eye_pitch_l");
  m.eye_pitch_r_ = signal("eye_pitch_r");
  m.neck_pan_ = signal("neck_pan");
  m.neck_tilt_ = signal("neck_tilt");
  m.neck_roll_ = signal("neck_roll");
  for (int f : {1, 2, 3, 14, 15, 19, 20, 21, 22, 23, 24, 25, 26, 48, 49, 50}) {
    m.supported_.set(static_cast<std::size_t>(f - 1));
  }

  // Muscle responses from the reduced face model: each group alone at
  // c = 0, 0.1, .., 1, jaw at rest, displacement of the point along the FAP.
  if (reduced.muscles.size() != L.muscle_count()) {
    throw ConfigError(head.file + ": the reduced face model has " +
                      std::to_string(reduced.muscles.size()) + " muscles, the head " +
                      std::to_string(L.muscle_count()));
  }
  face::ReducedFaceWorkspace ws = face::make_reduced_workspace(reduced);
  std::vector<double> c(reduced.muscles.size());
  std::vector<double> disp(3 * reduced.control_points.size());
  auto response = [&](const std::vector<const char*>& names, std::size_t point,
                      const face::Vec3& dir) {
    Response r;
    for (const char* n : names) {
      const auto i = L.find(n);
      if (!i || *i >= L.muscle_count()) {
        throw ConfigError(head.file + ": the FAP mapping needs muscle '" + std::string(n) +
                          "', which this head lacks");
      }
      r.muscles.push_back(*i);
    }
    for (std::size_t k = 0; k < r.along.size(); ++k) {
      std::fill(c.begin(), c.end(), 0.0);
      for (std::size_t i : r.muscles) c[i] = 0.1 * static_cast<double>(k);
      face::evaluate(reduced, ws, face::ReducedInput{.contractions = c}, disp);
      const face::Vec3 d(disp[3 * point], disp[3 * point + 1], disp[3 * point + 2]);
      // Running maximum: the inverse needs a monotone response.
      r.along[k] = std::max(k == 0 ? 0.0 : r.along[k - 1], d.dot(dir));
    }
    if (!(r.along.back() > 3e-4)) {  // 0.3 mm: the reduced model's relevance threshold
      throw ConfigError(head.file + ": muscle '" + std::string(names.front()) + "' does not move " +
                        std::string(reduced.control_points[point]) +
                        " in its FAP's direction in the reduced face model (" +
                        std::to_string(r.along.back() * 1e3) + " mm at c = 1)");
    }
    return r;
  };
  for (const auto& spec : muscle_route_specs()) {
    const auto& cps = reduced.control_points;
    const auto it = std::find(cps.begin(), cps.end(), spec.point);
    if (it == cps.end()) {
      throw ConfigError(head.file + ": the reduced face model lacks control point " +
                        std::string(spec.point) + " (FAP " + std::to_string(spec.fap) + ")");
    }
    const auto point = static_cast<std::size_t>(it - cps.begin());
    const face::Vec3 dir = direction_vector(fap_info(spec.fap).direction);
    MuscleRoute route;
    route.fap = spec.fap;
    route.point = spec.point;
    route.positive = response(spec.positive, point, dir);
    if (!spec.negative.empty()) {
      route.negative = response(spec.negative, point, -dir);
    }
    m.muscle_routes_.push_back(std::move(route));
    m.supported_.set(static_cast<std::size_t>(spec.fap - 1));
  }

  for (int e = 1; e <= 6; ++e) {
    const FacePose* pose = expressions.find(kExpressionNames[e]);
    if (pose == nullptr) {
      throw ConfigError(std::string("the expression library lacks '") + kExpressionNames[e] +
                        "', which FAP 2 (expression " + std::to_string(e) + ") needs");
    }
    m.expressions_[static_cast<std::size_t>(e)] = *pose;
  }
  for (int v = 0; v < VisemeTable::kCount; ++v) {
    m.visemes_[static_cast<std::size_t>(v)] = visemes.pose(v);
  }
  return m;
}

double FapMapping::pitch_for_open_jaw(double open_jaw, bool* reachable) const {
  return rotation_for_displacement(chin_, axes_.pitch_point, axes_.pitch_axis, {0, -1, 0},
                                   open_jaw * fapu_.unit(FapUnit::kMNS), reachable);
}

double FapMapping::contraction_for(const Response& r, double displacement) const {
  if (displacement <= 0.0) return 0.0;
  // Beyond c = 1 the response is extrapolated linearly so that the clamp
  // report says how far the request went.
  if (displacement >= r.along.back()) return displacement / r.along.back();
  for (std::size_t k = 1; k < r.along.size(); ++k) {
    if (displacement <= r.along[k]) {
      const double span = r.along[k] - r.along[k - 1];
      const double u = span > 0.0 ? (displacement - r.along[k - 1]) / span : 1.0;
      return 0.1 * (static_cast<double>(k - 1) + u);
    }
  }
  return 1.0;
}

void FapMapping::map(const FapState& s, long frame, std::array<double, kMaxFaceSignals>& out,
                     std::vector<FapClamp>* clamps) const {
  const std::size_t n = layout_.size();
  std::array<int, kMaxFaceSignals> driver{};
  out = neutral_;
  auto fap = [&](int f) { return s.values[static_cast<std::size_t>(f - 1)]; };

  // High-level FAPs: deltas from neutral, added.
  auto add_pose = [&](const FacePose& pose, double w, int by) {
    if (w <= 0.0) return;
    for (std::size_t i = 0; i < n; ++i) {
      if (!pose.set[i]) continue;
      out[i] += w * (pose.values[i] - neutral_[i]);
      driver[i] = by;
    }
  };
  const ExpressionParams& e = s.expression;
  if (e.select1 > 0)
    add_pose(expressions_[static_cast<std::size_t>(e.select1)], e.intensity1 / 63.0, 2);
  if (e.select2 > 0)
    add_pose(expressions_[static_cast<std::size_t>(e.select2)], e.intensity2 / 63.0, 2);
  const VisemeParams& v = s.viseme;
  const double b = v.blend / 63.0;
  add_pose(visemes_[static_cast<std::size_t>(v.select1)], 1.0 - b, 1);
  add_pose(visemes_[static_cast<std::size_t>(v.select2)], b, 1);

  auto report = [&](int f, const std::string& what, double requested, double applied,
                    const std::string& unit) {
    if (clamps) clamps->push_back({frame, f, what, requested, applied, unit});
  };
  // Unidirectional FAPs: negative values mean nothing; they count as 0.
  auto unidirectional = [&](int f) {
    const double x = fap(f);
    if (x < 0.0) {
      report(f, std::string(fap_info(f).name), x, 0.0, "FAP units");
      return 0.0;
    }
    return x;
  };

  // Jaw: displacements of the chin (fdp_2_1) through the mandible's geometry.
  const double open = unidirectional(3);
  if (open != 0.0) {
    out[layout_.jaw_pitch()] += pitch_for_open_jaw(open);
    driver[layout_.jaw_pitch()] = 3;
  }
  const double thrust = unidirectional(14);
  if (thrust != 0.0) {
    out[layout_.jaw_protrusion()] += thrust * fapu_.unit(FapUnit::kMNS) / axes_.protrusion_dir.z();
    driver[layout_.jaw_protrusion()] = 14;
  }
  if (fap(15) != 0.0) {
    out[layout_.jaw_yaw()] +=
        rotation_for_displacement(chin_, axes_.yaw_point, axes_.yaw_axis, {-1, 0, 0},
                                  fap(15) * fapu_.unit(FapUnit::kMW), nullptr);
    driver[layout_.jaw_yaw()] = 15;
  }

  // Eyelids: closure 1 closes the neutral gap IRISD0 = 1024 IRISD units.
  auto add = [&](std::size_t i, double x, int f) {
    if (x == 0.0) return;
    out[i] += x;
    driver[i] = f;
  };
  add(eyelid_l_, (fap(19) + fap(21)) / 1024.0, fap(19) != 0.0 ? 19 : 21);
  add(eyelid_r_, (fap(20) + fap(22)) / 1024.0, fap(20) != 0.0 ? 20 : 22);
  // Eyeballs and head: AU angles; + eye pitch / neck tilt look up (FAPs: + down).
  add(eye_yaw_l_, fap(23) * Fapu::kAu, 23);
  add(eye_yaw_r_, fap(24) * Fapu::kAu, 24);
  add(eye_pitch_l_, -fap(25) * Fapu::kAu, 25);
  add(eye_pitch_r_, -fap(26) * Fapu::kAu, 26);
  add(neck_tilt_, -fap(48) * Fapu::kAu, 48);
  add(neck_pan_, fap(49) * Fapu::kAu, 49);
  add(neck_roll_, fap(50) * Fapu::kAu, 50);

  // Muscles: each FAP asks a contraction of its group; a muscle several FAPs
  // drive (inner and outer lip FAPs name the same muscles) takes the largest.
  std::array<double, kMaxFaceSignals> demand{};
  for (const MuscleRoute& r : muscle_routes_) {
    double x = fap(r.fap);
    if (!fap_info(r.fap).bidirectional) x = unidirectional(r.fap);
    if (x == 0.0) continue;
    const double d = x * fapu_.unit(fap_info(r.fap).unit);
    const Response& resp = d > 0.0 ? r.positive : r.negative;
    if (resp.muscles.empty()) continue;
    const double cval = contraction_for(resp, std::abs(d));
    for (std::size_t i : resp.muscles) {
      if (cval > demand[i]) {
        demand[i] = cval;
        driver[i] = r.fap;
      }
    }
  }
  for (std::size_t i = 0; i < layout_.muscle_count(); ++i) out[i] += demand[i];

  // The envelope.
  for (std::size_t i = 0; i < n; ++i) {
    const double x = out[i];
    const double y = std::clamp(x, lo_[i], hi_[i]);
    if (y != x) {
      out[i] = y;
      report(driver[i] == 0 ? 2 : driver[i], layout_.signal(i).name, x, y,
             unit_of(layout_.signal(i)));
    }
  }
}

std::vector<FapRouteInfo> FapMapping::describe_routes() const {
  std::vector<FapRouteInfo> out;
  char buf[160];
  auto names = [&](const std::vector<std::size_t>& muscles) {
    std::string s;
    for (std::size_t i : muscles) s += (s.empty() ? "" : " + ") + layout_.signal(i).name;
    return s;
  };
  std::snprintf(buf, sizeof buf, "%.5f deg per unit at rest (MNS %.4f mm)",
                pitch_for_open_jaw(1.0) / kDeg, fapu_.unit(FapUnit::kMNS) * 1e3);
  out.push_back({3, "jaw_pitch (rotation about 2.14-2.13 lowering fdp_2_1)", buf});
  std::snprintf(buf, sizeof buf, "%.5f mm per unit",
                fapu_.unit(FapUnit::kMNS) * 1e3 / axes_.protrusion_dir.z());
  out.push_back({14, "jaw_protrusion (along 7.1-2.10, forward part = the FAP)", buf});
  std::snprintf(buf, sizeof buf, "%.5f deg per unit at rest (MW %.4f mm)",
                rotation_for_displacement(chin_, axes_.yaw_point, axes_.yaw_axis, {-1, 0, 0},
                                          fapu_.unit(FapUnit::kMW), nullptr) /
                    kDeg,
                fapu_.unit(FapUnit::kMW) * 1e3);
  out.push_back({15, "jaw_yaw (rotation about mid(2.13,2.14)-11.4 moving fdp_2_1 right)", buf});
  for (const MuscleRoute& r : muscle_routes_) {
    std::string target = "+ " + names(r.positive.muscles);
    std::snprintf(buf, sizeof buf, "c=1 moves %s %.2f mm", r.point.c_str(),
                  r.positive.along.back() * 1e3);
    std::string gain = buf;
    if (!r.negative.muscles.empty()) {
      target += " / - " + names(r.negative.muscles);
      std::snprintf(buf, sizeof buf, " / %.2f mm", r.negative.along.back() * 1e3);
      gain += buf;
    }
    out.push_back({r.fap, target, gain});
  }
  std::sort(out.begin(), out.end(),
            [](const FapRouteInfo& a, const FapRouteInfo& b) { return a.fap < b.fap; });
  return out;
}

FapMapping load_fap_mapping(const HeadConfig& head, const ExpressionLibrary& expressions,
                            const std::string& visemes_path) {
  std::string dir = std::filesystem::path(head.file).parent_path().string();
  if (dir.empty()) dir = ".";
  try {
    const face::HeadSpec spec = face::load_head_spec(dir);
    const face::ReducedFaceModel reduced =
        face::load_reduced_model(dir + "/reduced_face.txt", spec);
    const VisemeTable visemes = VisemeTable::load(visemes_path, head.layout);
    return FapMapping::build(head, FeaturePoints::load(spec), reduced, expressions, visemes);
  } catch (const face::InputError& e) {
    throw ConfigError(std::string(e.what()) + " (the FAP input reads this head's face model)");
  }
}

}  // namespace facectl
