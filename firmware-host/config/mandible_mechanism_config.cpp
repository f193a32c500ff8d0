#include "firmware-host/config/mandible_mechanism_config.hpp"

#include <algorithm>
#include <numbers>

#include "control/units.hpp"

namespace facectl {
namespace {

Eigen::Vector3d parse_point_mm(const ConfigNode& node) {
  const auto items = node.items();
  if (items.size() != 3) {
    node.fail("a point [x, y, z] in mm (head frame)", std::to_string(items.size()) + " numbers");
  }
  return Eigen::Vector3d(items[0].number(), items[1].number(), items[2].number()) * 1e-3;
}

MandibleDof parse_dof(const ConfigNode& node) {
  const std::string name = node.string();
  if (name == "pitch") return MandibleDof::kPitch;
  if (name == "yaw") return MandibleDof::kYaw;
  if (name == "protrusion") return MandibleDof::kProtrusion;
  node.fail("one of: pitch, yaw, protrusion", "'" + name + "'");
}

}  // namespace

MandibleMechanismConfig parse_mandible_mechanism(const ConfigNode& node) {
  node.expect_keys({"dofs", "held", "metric", "limits", "struts"});
  MandibleMechanismConfig out;
  out.where = node.where();
  for (const ConfigNode& d : node["dofs"].items()) {
    const MandibleDof dof = parse_dof(d);
    if (std::find(out.dofs.begin(), out.dofs.end(), dof) != out.dofs.end()) {
      d.fail("each degree of freedom once", "'" + d.string() + "' again");
    }
    out.dofs.push_back(dof);
  }
  const auto struts = node["struts"].items();
  if (struts.size() != out.dofs.size() || struts.size() < 2 || struts.size() > 3) {
    node["struts"].fail(
        "2 or 3 struts, one per entry of dofs (" + std::to_string(out.dofs.size()) + ")",
        std::to_string(struts.size()) + " struts");
  }
  for (const ConfigNode& s : struts) {
    s.expect_keys({"actuator", "skull_mm", "mandible_mm", "stroke_at_rest_mm"});
    StrutConfig strut;
    strut.where = s.where();
    strut.actuator = s["actuator"].string();
    for (const StrutConfig& other : out.struts) {
      if (other.actuator == strut.actuator) {
        s["actuator"].fail("an actuator that drives one strut only",
                           "'" + strut.actuator + "' again");
      }
    }
    strut.skull = parse_point_mm(s["skull_mm"]);
    strut.mandible = parse_point_mm(s["mandible_mm"]);
    if (auto r = s.get("stroke_at_rest_mm")) strut.stroke_at_rest = r->number() * 1e-3;
    out.struts.push_back(std::move(strut));
  }
  if (auto held = node.get("held")) {
    held->expect_keys({"pitch_deg", "yaw_deg", "protrusion_mm"});
    auto not_driven = [&](const char* key, MandibleDof dof) {
      const ConfigNode v = (*held)[key];
      if (std::find(out.dofs.begin(), out.dofs.end(), dof) != out.dofs.end()) {
        v.fail("only degrees of freedom the struts do not drive", std::string(key) + " (driven)");
      }
      return v.number();
    };
    if (held->has("pitch_deg"))
      out.held.pitch_rad = not_driven("pitch_deg", MandibleDof::kPitch) * kDeg;
    if (held->has("yaw_deg")) out.held.yaw_rad = not_driven("yaw_deg", MandibleDof::kYaw) * kDeg;
    if (held->has("protrusion_mm")) {
      out.held.protrusion_m = not_driven("protrusion_mm", MandibleDof::kProtrusion) * 1e-3;
    }
  }
  if (auto metric = node.get("metric")) {
    metric->expect_keys({"mm_per_deg"});
    // 1° counts as `mm_per_deg` millimetres when the IK clamps to the nearest pose.
    const double mm_per_deg = (*metric)["mm_per_deg"].positive();
    out.metric.angle_per_rad = mm_per_deg / kDeg;
    out.metric.length_per_m = 1000.0;
  }
  const ConfigNode limits = node["limits"];
  out.limits_where = limits.where();
  limits.expect_keys({"pitch", "yaw", "protrusion"});
  for (MandibleDof dof : out.dofs) {
    const bool angle = dof != MandibleDof::kProtrusion;
    const std::string u = angle ? "deg" : "mm";
    const double to_si = angle ? kDeg : 1e-3;
    const std::string name(to_string(dof));
    if (!limits.has(name)) limits.fail("limits for every driven DOF", "none for " + name);
    const ConfigNode l = limits[name];
    l.expect_keys(
        {"max_velocity_" + u + "_s", "max_acceleration_" + u + "_s2", "max_jerk_" + u + "_s3"});
    ActuatorLimits& out_l = out.limits[static_cast<std::size_t>(dof)];
    out_l.max_velocity = l["max_velocity_" + u + "_s"].positive() * to_si;
    out_l.max_acceleration = l["max_acceleration_" + u + "_s2"].positive() * to_si;
    if (auto j = l.get("max_jerk_" + u + "_s3")) out_l.max_jerk = j->non_negative() * to_si;
  }
  return out;
}

}  // namespace facectl
