#include "firmware-host/serve/api_json.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "firmware-host/model/model_builder.hpp"

namespace facectl {
namespace {

using nlohmann::json;

// Rounded to `per_unit` steps so the documents stay small: the nearest double to a short
// decimal prints as that decimal.
json rounded(std::span<const double> values, double per_unit) {
  json out = json::array();
  for (double v : values) out.push_back(std::round(v * per_unit) / per_unit);
  return out;
}

json named_points(const std::vector<std::string>& names, const std::vector<double>& mm) {
  json out = json::array();
  for (std::size_t i = 0; i < names.size(); ++i) {
    out.push_back(
        {{"name", names[i]}, {"position_mm", rounded(std::span(mm).subspan(3 * i, 3), 1e3)}});
  }
  return out;
}

}  // namespace

json state_json(const HeadService& service) {
  const HeadRuntime& head = service.head();
  json j;
  j["state"] = std::string(to_string(service.state()));
  json faults = json::array();
  if (auto f = service.active_fault()) {
    faults.push_back(
        {{"state", f->state}, {"reason", f->reason}, {"detail", f->detail}, {"time_s", f->time_s}});
  }
  j["faults"] = faults;
  j["faults_seen"] = head.controller->faults_seen();
  j["uptime_s"] = service.uptime_s();
  const FaceDirector::Status st = service.director().status();
  j["source"] = {{"kind", std::string(to_string(st.source))}, {"name", st.name}};
  j["show"] =
      st.source == FaceDirector::Source::kShow
          ? json{{"name", st.name}, {"position_s", st.position_s}, {"duration_s", st.duration_s}}
          : json(nullptr);
  j["queue"] = st.queue;
  j["loop"] = {{"ticks", head.stats.ticks.load()},
               {"overruns", head.stats.overruns.load()},
               {"alive", service.loop_alive()}};
  return j;
}

json rig_json(const HeadService& service) {
  const LoadedConfig& config = *service.head().cfg;
  const ControllerModel& m = config.built.model;
  json actuators = json::array();
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    const ActuatorModel& a = m.actuators[i];
    const double k = yaml_per_si(a.kind);
    // Where POST /api/v1/jog may take it; a mandible strut is never jogged alone.
    const HeadService::JogRange& r = service.jog_ranges()[i];
    const json jog =
        service.head().controller->is_strut(i) ? json(nullptr) : json{{"min", r.lo}, {"max", r.hi}};
    actuators.push_back({{"name", a.name},
                         {"unit", yaml_unit(a.kind)},
                         {"min", a.limits.position_min * k},
                         {"max", a.limits.position_max * k},
                         {"soft_min", a.limits.soft_min * k},
                         {"soft_max", a.limits.soft_max * k},
                         {"rest", a.rest * k},
                         {"jog", jog}});
  }
  const FaceBounds b = face_bounds(m);
  json signals = json::array();
  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    const SignalInfo& s = m.layout.signal(i);
    const double k = 1.0 / yaml_to_si(s.kind);
    signals.push_back({{"name", s.name},
                       {"key", yaml_key(s)},
                       {"unit", std::string(yaml_unit(s.kind))},
                       {"min", b.lo[i] * k},
                       {"max", b.hi[i] * k},
                       {"neutral", m.neutral[i] * k}});
  }
  return {{"rig", config.rig.name},
          {"head", config.head.name},
          {"rate_hz", m.rate_hz},
          {"actuators", actuators},
          {"signals", signals}};
}

namespace {

// Drive-level protection of the actuators with a `protection` block; an
// unreported reading is null.
json protection_json(const TelemetryRecord& rec, const ControllerModel& m) {
  const auto reading = [](float v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json out = json::array();
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    if (((rec.protected_mask >> i) & 1u) == 0) continue;
    out.push_back({{"actuator", m.actuators[i].name},
                   {"temperature_c", reading(rec.temperature_c[i])},
                   {"load", reading(rec.load[i])},
                   {"current_a", reading(rec.current_a[i])},
                   {"voltage_v", reading(rec.voltage_v[i])},
                   {"hardware_error", rec.hardware_error[i]},
                   {"derate", rec.derate[i]},
                   {"extreme_s", rec.extreme_s[i]},
                   {"state", to_string(static_cast<ProtectionMode>(rec.protection[i]))}});
  }
  return out;
}

}  // namespace

json telemetry_json(const TelemetryRecord& rec, const ControllerModel& m,
                    std::span<const double> landmarks_mm) {
  json commands = json::array();
  json measured = json::array();
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    const double k = yaml_per_si(m.actuators[i].kind);
    commands.push_back(rec.command[i] * k);
    measured.push_back(rec.feedback[i] * k);
  }
  json face = json::array();
  for (std::size_t i = 0; i < m.layout.size(); ++i) {
    face.push_back(rec.face[i] / yaml_to_si(m.layout.signal(i).kind));
  }
  json j{{"tick", rec.tick},
         {"time_s", rec.time_s},
         {"state", std::string(to_string(rec.state))},
         {"input_stale", rec.input_stale},
         {"commands", commands},
         {"measured", measured},
         {"face", face}};
  if (rec.protected_mask != 0) j["protection"] = protection_json(rec, m);
  if (!landmarks_mm.empty()) j["landmarks_mm"] = rounded(landmarks_mm, 1e4);
  return j;
}

json face_geometry_json(const FaceGeometry& g) {
  json edges = json::array();
  for (const auto& [a, b] : g.edges) edges.push_back({a, b});
  return {{"model", "reduced"},
          {"landmarks", named_points(g.points, g.points_mm)},
          {"anchors", named_points(g.anchors, g.anchors_mm)},
          {"edges", edges},
          {"skin", {{"vertices_mm", rounded(g.vertices_mm, 1e3)}, {"triangles", g.triangles}}},
          {"weights", rounded(g.weights, 1e6)}};
}

json events_json(const EventLog& log, std::size_t limit) {
  json events = json::array();
  for (const EventLog::Entry& e : log.recent(limit)) {
    events.push_back({{"time", e.time}, {"kind", e.kind}, {"source", e.source}, {"text", e.text}});
  }
  return {{"events", events}};
}

std::pair<std::size_t, double> checked_signal_value(const ControllerModel& m, const FaceBounds& b,
                                                    const std::string& key, double v,
                                                    const std::string& where) {
  const auto i = m.layout.find_yaml_key(key);
  if (!i) throw std::invalid_argument(where + ": no such signal on this head");
  const double k = yaml_to_si(m.layout.signal(*i).kind);
  if (!std::isfinite(v) || v * k < b.lo[*i] - 1e-12 || v * k > b.hi[*i] + 1e-12) {
    std::ostringstream e;
    e << where << ": expected " << b.lo[*i] / k << ".." << b.hi[*i] / k << ", found " << v;
    throw std::invalid_argument(e.str());
  }
  return {*i, v * k};
}

FaceDirector::Pose parse_pose_request(const json& body, const ControllerModel& m,
                                      std::string& summary) {
  if (!body.is_object() || !body.contains("signals") || !body["signals"].is_object()) {
    throw std::invalid_argument("expected {\"signals\": {\"<signal key>\": value, ...}}");
  }
  const FaceBounds b = face_bounds(m);
  FaceDirector::Pose pose = m.neutral;
  std::ostringstream text;
  for (const auto& [key, value] : body["signals"].items()) {
    if (!m.layout.find_yaml_key(key)) {
      throw std::invalid_argument("signals." + key + ": no such signal on this head");
    }
    if (!value.is_number()) {
      throw std::invalid_argument("signals." + key + ": expected a number, found " + value.dump());
    }
    const double v = value.get<double>();
    const auto [i, si] = checked_signal_value(m, b, key, v, "signals." + key);
    pose[i] = si;
    text << (text.tellp() > 0 ? ", " : "") << key << "=" << v;
  }
  summary = text.str();
  return pose;
}

}  // namespace facectl
