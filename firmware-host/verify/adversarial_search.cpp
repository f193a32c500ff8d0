#include "firmware-host/verify/adversarial_search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>

#include "control/units.hpp"
#include "firmware-host/run/offline_head.hpp"

namespace facectl::verify {
namespace {

using Severity = Finding::Severity;
constexpr std::size_t kMaxReported = 40;

enum class Mode { kUniform, kExtremes, kBangBang, kNeutral, kNaN };

// The search drives the controller with a million ticks of bang-bang and
// extreme input, which no servo's thermal rating is meant to survive: it
// checks the control law's limits, so the simulated servos keep their thermal
// statistics but never trip (a show's own load is checked by show_check).
// Drive-level protection likewise derates and cools down but never faults:
// its derating stays in the search, so every limit is checked with it.
LoadedConfig without_servo_overload(LoadedConfig cfg) {
  for (ActuatorConfig& a : cfg.rig.actuators) a.plant.thermal.trips = false;
  for (DriveProtection& p : cfg.built.model.protection) p.faults = false;
  return cfg;
}

class Search {
 public:
  Search(const LoadedConfig& cfg, const SearchOptions& o)
      : head_(without_servo_overload(cfg), 0, true), m_(head_.model()), rng_(o.seed), options_(o) {
    for (const ActuatorModel& a : m_.actuators) result_.actuators.push_back({a.name});
    prev_cmd_.fill(0.0);
  }

  SearchResult run() {
    const auto start = std::chrono::steady_clock::now();
    head_.controller().request_enable();
    const double period = head_.period();
    std::array<double, kMaxFaceSignals> values = m_.neutral;
    std::uint64_t segment_left = 0;
    Mode mode = Mode::kNeutral;
    double dt_scale = 1.0;
    for (std::uint64_t t = 0; t < options_.ticks; ++t) {
      if (segment_left == 0) {
        segment_left = 1 + rng_() % 400;
        const auto pick = rng_() % 100;
        mode = pick < 40   ? Mode::kUniform
               : pick < 70 ? Mode::kExtremes
               : pick < 90 ? Mode::kBangBang
               : pick < 98 ? Mode::kNeutral
                           : Mode::kNaN;
        // One segment in four runs with late and early ticks.
        dt_scale = rng_() % 4 == 0 ? 0.5 + 2.5 * unit() : 1.0;
        if (mode != Mode::kBangBang) draw(mode, values);
      }
      --segment_left;
      if (mode == Mode::kBangBang) draw(Mode::kExtremes, values);
      head_.send(values);
      const double dt = dt_scale == 1.0 ? period : period * (0.5 + (dt_scale - 0.5) * unit());
      head_.step(dt);
      measure(dt);
    }
    result_.ticks = options_.ticks;
    result_.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (std::size_t i = 0; i < m_.actuators.size(); ++i) {
      if (jerk_yields_[i] == 0) continue;
      result_.findings.push_back(
          {Severity::kWarn, "jerk", m_.actuators[i].name,
           "the jerk limit yielded to a hard bound (position, velocity or acceleration) on " +
               std::to_string(jerk_yields_[i]) + " ticks: by design (docs/SAFETY.md, jerk yielded)",
           ""});
    }
    for (const FaultGroup& g : faults_) {
      char first[48];
      std::snprintf(first, sizeof first, ", first at t = %.4f s", g.first_s);
      result_.findings.push_back({Severity::kFail, "fault", g.subject,
                                  "the controller entered " + g.state + " (" + g.reason + ") " +
                                      std::to_string(g.count) + " time(s)" + first + g.first_detail,
                                  ""});
    }
    if (limit_violations_ > kMaxReported) {
      result_.findings.push_back({Severity::kFail, "adversarial", "",
                                  std::to_string(limit_violations_) + " limit violations in all; " +
                                      std::to_string(kMaxReported) + " listed",
                                  ""});
    }
    return std::move(result_);
  }

 private:
  double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }

  void draw(Mode mode, std::array<double, kMaxFaceSignals>& v) {
    for (std::size_t i = 0; i < m_.layout.size(); ++i) {
      const SignalInfo& s = m_.layout.signal(i);
      switch (mode) {
        case Mode::kUniform:
          v[i] = s.domain_min + (s.domain_max - s.domain_min) * unit();
          break;
        case Mode::kExtremes:
        case Mode::kBangBang:
          v[i] = rng_() % 2 ? s.domain_max : s.domain_min;
          break;
        case Mode::kNeutral:
          v[i] = m_.neutral[i];
          break;
        case Mode::kNaN:
          v[i] = rng_() % 3 == 0 ? std::numeric_limits<double>::quiet_NaN() : m_.neutral[i];
          break;
      }
    }
  }

  void violation(const std::string& check, const std::string& subject, const std::string& what) {
    ++result_.violations;
    if (++limit_violations_ > kMaxReported) return;
    char at[48];
    std::snprintf(at, sizeof at, " at t = %.4f s", head_.time() - 1.0);
    result_.findings.push_back({Severity::kFail, check, subject, what + at, ""});
  }

  // A fault, once per kind: the reason the state machine gave and the subject
  // it concerns, counted, with the first time and what was measured then. The
  // search re-enables after each, so one cause can fault many times.
  struct FaultGroup {
    std::string state, subject, reason, first_detail;
    std::uint64_t count = 0;
    double first_s = 0.0;
  };

  // Who a fault is about, and what the controller saw of it.
  std::pair<std::string, std::string> fault_subject(TransitionReason reason) {
    const Controller& c = head_.controller();
    std::string subject, detail;
    auto add = [&](const ActuatorModel& a, const std::string& what) {
      subject += (subject.empty() ? "" : ", ") + a.name;
      if (detail.empty()) detail = " (" + a.name + " " + what + ")";
    };
    for (std::size_t i = 0; i < m_.actuators.size(); ++i) {
      const ActuatorModel& a = m_.actuators[i];
      const double s = yaml_per_si(a.kind), x = c.measured()[i];
      const char* u = yaml_unit(a.kind);
      char buf[160];
      if (reason == TransitionReason::kFeedbackOutOfRange &&
          !(a.limits.position_min <= x && x <= a.limits.position_max)) {
        std::snprintf(buf, sizeof buf,
                      "measured at %.4g %s, outside its hardware range %.4g..%.4g %s", x * s, u,
                      a.limits.position_min * s, a.limits.position_max * s, u);
        add(a, buf);
      }
      if (reason == TransitionReason::kLimitBreach && (c.limit_flags()[i] & kLimitBreach) != 0) {
        add(a, "commanded outside its hardware range");
      }
      if (reason == TransitionReason::kBusFault && last_detail_.find(a.name) != std::string::npos &&
          subject.empty()) {
        subject = a.name;
      }
    }
    if (!subject.empty()) return {subject, detail};
    switch (reason) {
      case TransitionReason::kFeedbackOutOfRange:
        return {"jaw struts", " (the measured strut lengths put the jaw outside the envelope)"};
      case TransitionReason::kBusFault:
        return {"bus", ""};
      case TransitionReason::kOverrunStorm:
        return {"loop", ""};
      default:
        return {"safety I/O", ""};
    }
  }

  void fault(SafetyState state) {
    ++result_.violations;
    const auto [subject, detail] = fault_subject(last_reason_);
    std::string reason(to_string(last_reason_));
    if (!last_detail_.empty()) reason += ": " + last_detail_;
    const std::string name(to_string(state));
    for (FaultGroup& g : faults_) {
      if (g.state == name && g.subject == subject && g.reason == reason) {
        ++g.count;
        return;
      }
    }
    faults_.push_back({name, subject, reason, detail, 1, head_.time() - 1.0});
  }

  void measure(double dt) {
    Controller& c = head_.controller();
    while (const TransitionEvent* ev = head_.events().front()) {
      if (ev->to == SafetyState::kFault || ev->to == SafetyState::kEstop) {
        last_reason_ = ev->reason;
        last_detail_ = ev->detail;
      }
      head_.events().pop();
    }
    const SafetyState state = c.state();
    if (state == SafetyState::kFault || state == SafetyState::kEstop) {
      if (!in_fault_) fault(state);  // once per entry, not per tick until the reset
      in_fault_ = true;
      c.request_reset();
      c.request_enable();
      live_ = false;
      return;
    }
    in_fault_ = false;
    const bool live = commands_actuators(state);
    if (state == SafetyState::kIdle) c.request_enable();
    const auto& cmd = c.commands();
    const std::size_t n = m_.actuators.size();
    if (live && live_) {
      for (std::size_t i = 0; i < n; ++i) check_actuator(i, cmd[i], dt);
      check_constraints(cmd);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double v = (cmd[i] - prev_cmd_[i]) / dt;
      const double a = (v - prev_vel_[i]) / dt;
      prev_acc_[i] = live && live_ ? a : 0.0;
      prev_vel_[i] = live && live_ ? v : 0.0;
      prev_cmd_[i] = cmd[i];
    }
    live_ = live;
  }

  void check_actuator(std::size_t i, double x, double dt) {
    const ActuatorModel& a = m_.actuators[i];
    const ActuatorLimits& l = a.limits;
    ActuatorMargins& mg = result_.actuators[i];
    const double s = yaml_per_si(a.kind);
    const double hw = std::min(x - l.position_min, l.position_max - x) * s;
    if (hw < mg.hardware) {
      mg.hardware = hw;
      mg.hardware_at_s = head_.time() - 1.0;
    }
    const double soft = std::min(x - l.soft_min, l.soft_max - x) * s;
    mg.soft = std::min(mg.soft, soft);
    const double v = (x - prev_cmd_[i]) / dt;
    const double acc = (v - prev_vel_[i]) / dt;
    const double fv = 1.0 - std::fabs(v) / l.max_velocity;
    const double fa = 1.0 - std::fabs(acc) / l.max_acceleration;
    mg.velocity = std::min(mg.velocity, fv);
    mg.acceleration = std::min(mg.acceleration, fa);
    if (l.max_jerk > 0.0) {
      const double fj = 1.0 - std::fabs((acc - prev_acc_[i]) / dt) / l.max_jerk;
      mg.jerk = std::min(mg.jerk, fj);
      if (fj < -1e-6) ++jerk_yields_[i];
    }
    constexpr double kTol = 1e-6;  // relative: rounding in the finite differences
    if (hw < 0.0) violation("position", a.name, "command outside the hardware range");
    if (soft < -1e-9 * s) violation("position", a.name, "command outside the soft range");
    if (fv < -kTol) violation("velocity", a.name, "velocity beyond max_velocity");
    if (fa < -kTol) violation("acceleration", a.name, "acceleration beyond max_acceleration");
  }

  void check_constraints(const std::array<double, kMaxActuators>& cmd) {
    const auto& face = head_.controller().face();
    for (std::size_t k = 0; k < m_.face_constraints.size(); ++k) {
      const auto& con = m_.face_constraints.constraint(k);
      const double margin = con.bound - con.value(face.data());
      result_.face_constraint_margin = std::min(result_.face_constraint_margin, margin);
      if (margin < -1e-9) violation("face coupled limit", con.name, "face pose beyond the limit");
    }
    for (std::size_t k = 0; k < m_.actuator_constraints.size(); ++k) {
      const auto& con = m_.actuator_constraints.constraint(k);
      const double margin = con.bound - con.value(cmd.data());
      result_.actuator_constraint_margin = std::min(result_.actuator_constraint_margin, margin);
      if (margin < -1e-9)
        violation("actuator coupled limit", con.name, "commands beyond the limit");
    }
    const double pitch = face[m_.layout.jaw_pitch()], yaw = face[m_.layout.jaw_yaw()],
                 prot = face[m_.layout.jaw_protrusion()];
    const double e =
        std::min({pitch - m_.envelope.pitch.min, m_.envelope.pitch.max - pitch,
                  yaw - m_.envelope.yaw.min, m_.envelope.yaw.max - yaw,
                  prot - m_.envelope.protrusion.min, m_.envelope.protrusion.max - prot});
    result_.envelope_margin = std::min(result_.envelope_margin, e);
    if (e < -1e-12) violation("mandible envelope", "jaw", "face pose outside the envelope");
    if (m_.mapping.mechanism) check_mechanism(cmd);
  }

  // The pose the struts' limited commands actually put the jaw in (forward
  // kinematics): each strut is limited on its own, so in a fast move the
  // struts' pose can differ from the face's.
  void check_mechanism(const std::array<double, kMaxActuators>& cmd) {
    const MandibleMechanism& mech = *m_.mapping.mechanism;
    MandibleStrokes strokes{};
    for (std::size_t i = 0; i < mech.struts(); ++i) strokes[i] = cmd[mech.strut[i].actuator];
    const auto pose = forward(mech, strokes, mechanism_pose_);
    if (!pose) {
      violation("mandible mechanism", "jaw", "strut commands that are no pose of the mandible");
      return;
    }
    mechanism_pose_ = *pose;
    const MandibleEnvelope& env = m_.envelope;
    const double e = std::min({pose->pitch_rad - env.pitch.min, env.pitch.max - pose->pitch_rad,
                               pose->yaw_rad - env.yaw.min, env.yaw.max - pose->yaw_rad,
                               pose->protrusion_m - env.protrusion.min,
                               env.protrusion.max - pose->protrusion_m});
    result_.mechanism_envelope_margin = std::min(result_.mechanism_envelope_margin, e);
    if (e < -1e-9) {
      violation("mandible envelope", "jaw struts",
                "strut commands put the jaw outside the envelope");
    }
  }

  OfflineHead head_;
  const ControllerModel& m_;
  std::mt19937_64 rng_;
  SearchOptions options_;
  SearchResult result_;
  bool live_ = false;
  bool in_fault_ = false;
  TransitionReason last_reason_ = TransitionReason::kNone;  // of the last fault's transition
  std::string last_detail_;
  std::vector<FaultGroup> faults_;
  std::uint64_t limit_violations_ = 0;  // the violations but the faults: listed one by one
  face::MandiblePose mechanism_pose_;   // last forward-kinematics pose: the next guess
  std::array<double, kMaxActuators> prev_cmd_{}, prev_vel_{}, prev_acc_{};
  std::array<std::uint64_t, kMaxActuators> jerk_yields_{};
};

}  // namespace

SearchResult adversarial_search(const LoadedConfig& cfg, const SearchOptions& options) {
  return Search(cfg, options).run();
}

}  // namespace facectl::verify
