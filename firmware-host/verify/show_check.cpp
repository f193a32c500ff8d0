#include "firmware-host/verify/show_check.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "control/units.hpp"
#include "firmware-host/cli/plot_command.hpp"
#include "firmware-host/report/telemetry_csv.hpp"
#include "firmware-host/run/offline_head.hpp"
#include "firmware-host/run/telemetry_writer.hpp"

namespace facectl::verify {
namespace {

struct Open {
  Engagement e;
  std::uint64_t last_tick = 0;
};

class Collector {
 public:
  void see(std::uint64_t tick, double t, const std::string& kind, const std::string& subject,
           double size, const std::string& unit) {
    const std::string key = kind + "/" + subject;
    auto it = open_.find(key);
    // Ticks closer than kGap apart belong to one engagement.
    constexpr std::uint64_t kGap = 50;
    if (it != open_.end() && it->second.last_tick + kGap >= tick) {
      it->second.e.end_s = t;
      it->second.e.size = std::max(it->second.e.size, size);
      it->second.last_tick = tick;
      return;
    }
    if (it != open_.end()) done_.push_back(it->second.e);
    open_[key] = {{kind, subject, t, t, size, unit}, tick};
  }
  std::vector<Engagement> finish() {
    for (auto& [k, o] : open_) done_.push_back(o.e);
    std::sort(done_.begin(), done_.end(), [](const Engagement& a, const Engagement& b) {
      return a.start_s != b.start_s ? a.start_s < b.start_s : a.subject < b.subject;
    });
    return done_;
  }

 private:
  std::map<std::string, Open> open_;
  std::vector<Engagement> done_;
};

// The states a show may pass through: anything else (FAULT, ESTOP) fails it.
bool live(SafetyState s) {
  return s == SafetyState::kIdle || commands_actuators(s);
}

// Watches the controller's state on every tick, and its transitions (the
// events ring) for the reason it left the live states.
class FaultWatch {
 public:
  explicit FaultWatch(OfflineHead& head) : head_(head) {}

  void see(double t, std::optional<ShowFault>& fault) {
    while (const TransitionEvent* ev = head_.events().front()) {
      if (!live(ev->to)) {
        reason_ = std::string(to_string(ev->reason));
        if (ev->detail[0] != '\0') reason_ += std::string(" — ") + ev->detail;
      }
      head_.events().pop();
    }
    const SafetyState s = head_.controller().state();
    if (live(s)) return;
    if (!fault) fault = ShowFault{std::string(to_string(s)), std::max(0.0, t), reason_, 0};
    ++fault->ticks;
  }

 private:
  OfflineHead& head_;
  std::string reason_ = "no transition recorded";
};

}  // namespace

bool ShowCheck::passed() const {
  return clean() && !fault;
}

bool ShowCheck::clean() const {
  return std::none_of(engagements.begin(), engagements.end(), [](const Engagement& e) {
    return e.kind == "envelope" || e.kind == "position" || e.kind == "coupled" ||
           e.kind == "actuator coupled" || e.kind == "mapping";
  });
}

ShowCheck check_show(const LoadedConfig& base, const std::string& show_path,
                     const std::string& out_dir) {
  LoadedConfig cfg = base;
  cfg.show = Show::load(show_path, cfg.head.layout, cfg.head.neutral, cfg.expressions);
  const Show& show = *cfg.show;
  ShowCheck out;
  out.show = show_path;
  out.duration_s = show.duration();

  OfflineHead head(cfg, 1024, true);
  const ControllerModel& m = head.model();
  FaultWatch watch(head);
  // Enable on the neutral pose first: the show starts once RUNNING.
  head.send(m.neutral);
  head.controller().request_enable();
  while (head.controller().state() != SafetyState::kRunning && head.time() < 30.0) {
    head.step(head.period());
    watch.see(0.0, out.fault);
    while (head.telemetry()->front()) head.telemetry()->pop();
  }
  std::FILE* csv = nullptr;
  if (!out_dir.empty()) {
    std::filesystem::create_directories(out_dir);
    out.telemetry_csv = out_dir + "/telemetry.csv";
    csv = std::fopen(out.telemetry_csv.c_str(), "w");
    if (csv == nullptr) throw std::runtime_error(out.telemetry_csv + ": cannot write");
    TelemetryWriter::write_header(csv, m);
  }
  Collector seen;
  const double t0 = head.time();
  const double show_period = 1.0 / std::max(1.0, cfg.runtime.show_rate_hz);
  double next_pose = 0.0;
  std::array<double, kMaxFaceSignals> pose{};
  const double end = show.duration() + 0.5;  // and half a second to settle
  std::uint64_t tick = 0;
  while (head.time() - t0 < end) {
    const double t = head.time() - t0;
    if (t >= next_pose) {
      show.evaluate(std::min(t, show.duration()), pose);
      head.send(pose);
      next_pose += show_period;
    }
    head.step(head.period());
    ++tick;
    watch.see(t, out.fault);
    const Controller& c = head.controller();
    if (c.envelope_excess() > 0.0) seen.see(tick, t, "envelope", "face", c.envelope_excess(), "SI");
    for (std::size_t k = 0; k < m.face_constraints.size(); ++k) {
      if ((c.coupled_flags() >> k) & 1u) {
        seen.see(tick, t, "coupled", m.face_constraints.constraint(k).name, c.coupled_violation(),
                 "");
      }
    }
    for (std::size_t k = 0; k < m.actuator_constraints.size(); ++k) {
      if ((c.actuator_coupled_flags() >> k) & 1u) {
        seen.see(tick, t, "actuator coupled", m.actuator_constraints.constraint(k).name,
                 c.actuator_coupled_violation(), "");
      }
    }
    while (const TelemetryRecord* r = head.telemetry()->front()) {
      for (std::size_t i = 0; i < m.actuators.size(); ++i) {
        const LimitFlags f = r->limits[i];
        if (f == 0) continue;
        const ActuatorModel& a = m.actuators[i];
        const double gap = std::fabs(c.targets()[i] - r->command[i]) * yaml_per_si(a.kind);
        const std::string unit = yaml_unit(a.kind);
        const std::pair<LimitFlags, const char*> kinds[] = {
            {kLimitPosition, "position"},         {kLimitVelocity, "velocity"},
            {kLimitAcceleration, "acceleration"}, {kLimitJerk, "jerk"},
            {kLimitApproach, "approach"},         {kLimitCoupled, "actuator coupled bound"},
            {kLimitMapping, "mapping"},           {kLimitBreach, "breach"}};
        for (const auto& [bit, name] : kinds) {
          if ((f & bit) != 0) seen.see(tick, t, name, a.name, gap, unit);
        }
      }
      if (csv != nullptr) TelemetryWriter::write_row(csv, *r);
      head.telemetry()->pop();
    }
  }
  out.engagements = seen.finish();
  if (csv != nullptr) {
    std::fclose(csv);
    out.plots = write_actuator_plots(m, read_telemetry_csv(out.telemetry_csv), {}, out_dir);
  }
  return out;
}

}  // namespace facectl::verify
