#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <utility>

#include "control/telemetry_record.hpp"
#include "firmware-host/model/model_builder.hpp"
#include "firmware-host/serve/face_geometry.hpp"
#include "firmware-host/serve/head_service.hpp"

namespace facectl {

// The JSON documents of the HTTP API (docs/API.md). Values are in the units
// the YAML files use: deg for rotary actuators and angles, mm for linear ones.
nlohmann::json state_json(const HeadService& service);
// Each actuator's `jog` is its HeadService::JogRange, or null for a strut.
nlohmann::json rig_json(const HeadService& service);
// `landmarks_mm`, when given: the control points' displacements (FaceLandmarks).
nlohmann::json telemetry_json(const TelemetryRecord& rec, const ControllerModel& model,
                              std::span<const double> landmarks_mm = {});
nlohmann::json face_geometry_json(const FaceGeometry& geometry);
nlohmann::json events_json(const EventLog& log, std::size_t limit);

// Signal `key` (its YAML key, e.g. jaw_pitch_deg) at `v` in its YAML unit:
// its index and SI value, inside the face's bounds. Throws
// std::invalid_argument "<where>: no such signal on this head" or
// "<where>: expected lo..hi, found v".
std::pair<std::size_t, double> checked_signal_value(const ControllerModel& m, const FaceBounds& b,
                                                    const std::string& key, double v,
                                                    const std::string& where);

// The pose of POST /api/v1/pose: {"signals": {"jaw_pitch_deg": 6, ...}} over
// the neutral face. Throws std::invalid_argument naming the key for an
// unknown signal, a value that is not a number, or one outside the range the
// tick admits (the envelope for the jaw).
FaceDirector::Pose parse_pose_request(const nlohmann::json& body, const ControllerModel& model,
                                      std::string& summary);

}  // namespace facectl
