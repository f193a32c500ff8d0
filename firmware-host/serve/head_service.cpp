#include "firmware-host/serve/head_service.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "control/realtime/loop_timer.hpp"
#include "firmware-host/serve/loop_watchdog.hpp"
#include "firmware-host/serve/systemd_notify.hpp"
#include "firmware-host/verify/static_proof.hpp"

namespace facectl {
namespace {

bool faulted(SafetyState s) {
  return s == SafetyState::kFault || s == SafetyState::kEstop;
}

std::string state_name(SafetyState s) {
  return std::string(to_string(s));
}

HeadService::Result refuse(int status, std::string why) {
  return {status, std::move(why)};
}

}  // namespace

HeadService::HeadService(HeadRuntime& head, FaceDirector& director, const ShowCatalog& shows,
                         EventLog& log)
    : head_(head), director_(director), shows_(shows), log_(log), start_ns_(monotonic_ns()) {}

const std::vector<HeadService::JogRange>& HeadService::jog_ranges() const {
  std::call_once(jog_proven_, [this] {
    // The static proof's ranges are in file order of the rig's actuators, by name: the
    // same proof as `facectl verify`, so a jog range is what verify reports.
    const verify::StaticProof proof = verify::prove(*head_.cfg);
    verify::release_lp_thread_state();  // the API's worker threads end without GLPK
    const ControllerModel& m = head_.model();
    for (const ActuatorModel& a : m.actuators) {
      const double k = yaml_per_si(a.kind);
      JogRange r{a.limits.soft_min * k, a.limits.soft_max * k};
      for (const verify::ActuatorRange& p : proof.actuators) {
        if (p.name == a.name) r = {std::max(r.lo, p.lo), std::min(r.hi, p.hi)};
      }
      jog_ranges_.push_back(r);
    }
  });
  return jog_ranges_;
}

HeadService::~HeadService() {
  stop_monitor();
}

void HeadService::start_monitor() {
  thread_ = std::thread([this] { monitor(); });
}

void HeadService::stop_monitor() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
  drain_events();  // what the loop said last
}

double HeadService::uptime_s() const {
  return static_cast<double>(monotonic_ns() - start_ns_) * 1e-9;
}

void HeadService::drain_events() {
  while (const TransitionEvent* ev = head_.events.front()) {
    std::string text = state_name(ev->from) + " -> " + state_name(ev->to) + ": " +
                       std::string(to_string(ev->reason));
    if (ev->detail[0] != '\0') text += " (" + std::string(ev->detail) + ")";
    const bool fault = faulted(ev->to);
    log_.add(fault ? "fault" : "transition", "loop", text);
    {
      const std::lock_guard lock(mutex_);
      if (fault) {
        fault_ = ActiveFault{state_name(ev->to), std::string(to_string(ev->reason)), ev->detail,
                             ev->time_s};
      } else {
        fault_.reset();
      }
    }
    notify_status(state_name(ev->to));
    head_.events.pop();
  }
  if (const std::uint64_t lost = head_.events.dropped(); lost > 0) {
    // Not expected (256 transitions between two 10 ms drains); said, not hidden.
    if (lost != events_lost_said_) {
      log_.add("service", "loop", std::to_string(lost - events_lost_said_) + " transitions lost");
    }
    events_lost_said_ = lost;
  }
}

void HeadService::monitor() {
  LoopWatchdog watchdog(std::chrono::milliseconds(100));
  while (!stop_.load(std::memory_order_relaxed)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    drain_events();
    if (head_.telemetry) {
      std::uint64_t n = 0;
      while (const TelemetryRecord* rec = head_.telemetry->front()) {
        newest_ = *rec;  // the newest matters here; a plain copy, off the real-time thread
        head_.telemetry->pop();
        ++n;
      }
      if (n > 0) {
        const std::lock_guard lock(mutex_);
        latest_ = newest_;
        taken_ += n;
      }
    }
    if (watchdog.look(head_.stats.ticks.load(std::memory_order_relaxed),
                      std::chrono::steady_clock::now())) {
      loop_alive_.store(watchdog.alive(), std::memory_order_relaxed);
      if (watchdog.alive()) notify_watchdog();
    }
  }
}

std::uint64_t HeadService::latest(TelemetryRecord& out) const {
  const std::lock_guard lock(mutex_);
  out = latest_;
  return taken_;
}

std::optional<HeadService::ActiveFault> HeadService::active_fault() const {
  const SafetyState s = state();
  if (!faulted(s)) return std::nullopt;
  const std::lock_guard lock(mutex_);
  // The monitor reads the transition within 10 ms of the state changing.
  return fault_ ? fault_ : ActiveFault{state_name(s), "not yet reported", "", 0.0};
}

bool HeadService::wait_for_state_change(SafetyState from, double seconds) const {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    if (state() != from) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return state() != from;
}

std::optional<HeadService::Result> HeadService::refuse_if_stopping() const {
  if (!stopping_.load()) return std::nullopt;
  return refuse(503, "the service is stopping: the head eases to rest");
}

void HeadService::begin_shutdown(const std::string& who) {
  stopping_.store(true);
  log_.add("service", who, "easing to rest and stopping");
  head_.controller->request_shutdown();
}

HeadService::Result HeadService::enable(const std::string& who) {
  if (auto r = refuse_if_stopping()) return *r;
  const SafetyState s = state();
  if (faulted(s)) {
    return refuse(409, "the head is in " + state_name(s) + ": reset it first");
  }
  if (s == SafetyState::kStopping) {
    return refuse(409, "the head is easing to rest (STOPPING): enable it once it is IDLE");
  }
  log_.add("command", who, "enable");
  head_.controller->request_enable();
  return {};
}

HeadService::Result HeadService::disable(const std::string& who) {
  log_.add("command", who, "disable");
  head_.controller->request_shutdown();
  return {};
}

HeadService::Result HeadService::reset(const std::string& who, bool then_enable) {
  if (auto r = refuse_if_stopping()) return *r;
  const SafetyState s = state();
  if (!faulted(s)) return refuse(409, "nothing to reset: the head is " + state_name(s));
  log_.add("command", who, then_enable ? "reset and enable" : "reset");
  head_.controller->request_reset();
  // The tick takes the request on its next step; allow a few periods.
  const double wait_s = std::max(0.1, 5.0 / head_.model().rate_hz);
  if (!wait_for_state_change(s, wait_s)) {
    const std::string why = s == SafetyState::kEstop
                                ? "the e-stop is still pressed: release it, then reset"
                                : "the fault's cause is still present";
    log_.add("command", who, "reset refused: " + why);
    return refuse(409, "reset refused: " + why);
  }
  if (then_enable) head_.controller->request_enable();
  return {};
}

HeadService::Result HeadService::jog_start(const std::string& who) {
  jog_ranges();  // proven before the checks, so none of them is stale when JOG is asked for
  if (auto r = refuse_if_stopping()) return *r;
  const SafetyState s = state();
  if (s == SafetyState::kJog) return {};
  if (s != SafetyState::kRunning) {
    return refuse(409, "JOG starts from RUNNING; the head is " + state_name(s));
  }
  log_.add("command", who, "jog start");
  head_.controller->request_jog(true);
  // Answer once the tick took it, so a jog right after is not refused.
  wait_for_state_change(s, std::max(0.1, 5.0 / head_.model().rate_hz));
  return {};
}

HeadService::Result HeadService::jog_stop(const std::string& who) {
  const SafetyState s = state();
  if (s != SafetyState::kJog) return refuse(409, "not jogging: the head is " + state_name(s));
  log_.add("command", who, "jog stop");
  head_.controller->request_jog(false);
  wait_for_state_change(s, std::max(0.1, 5.0 / head_.model().rate_hz));
  return {};
}

HeadService::Result HeadService::jog(const std::string& who, const std::string& actuator,
                                     double position) {
  if (auto r = refuse_if_stopping()) return *r;
  const ControllerModel& m = head_.model();
  std::size_t i = 0;
  while (i < m.actuators.size() && m.actuators[i].name != actuator) ++i;
  if (i == m.actuators.size()) return refuse(404, "no actuator '" + actuator + "' on this rig");
  const SafetyState s = state();
  if (s != SafetyState::kJog) {
    return refuse(
        409, "jogging needs the JOG state (POST /api/v1/jog/start); the head is " + state_name(s));
  }
  if (head_.controller->is_strut(i)) {
    return refuse(409, actuator +
                           " is a strut of the mandible mechanism: it moves only with the "
                           "others, by the jaw's pose");
  }
  const ActuatorModel& a = m.actuators[i];
  const JogRange& r = jog_ranges()[i];
  constexpr double kSlack = 1e-9;  // the YAML value back from SI
  if (!std::isfinite(position) || position < r.lo - kSlack || position > r.hi + kSlack) {
    std::ostringstream e;
    e << "position of " << actuator << ": expected " << r.lo << ".." << r.hi
      << " (its soft range, within where an admissible face takes it), found " << position;
    return refuse(422, e.str());
  }
  log_.add("command", who, "jog " + actuator + " to " + std::to_string(position));
  head_.controller->request_jog_target(i, std::clamp(position, r.lo, r.hi) / yaml_per_si(a.kind));
  return {};
}

HeadService::Result HeadService::play(const std::string& who, const std::string& name, bool queue) {
  if (auto r = refuse_if_stopping()) return *r;
  std::shared_ptr<const Show> show;
  try {
    show = shows_.load(name);
  } catch (const std::out_of_range& e) {
    return refuse(404, e.what());
  } catch (const std::exception& e) {
    return refuse(422, std::string("show '") + name + "' does not load: " + e.what());
  }
  log_.add("command", who, (queue ? "queue show " : "play show ") + name);
  if (queue) {
    director_.enqueue(std::move(show), name);
  } else {
    director_.play(std::move(show), name);
  }
  return {};
}

HeadService::Result HeadService::stop_show(const std::string& who) {
  log_.add("command", who, "stop show");
  director_.stop_show();
  return {};
}

HeadService::Result HeadService::hold_expression(const std::string& who, const std::string& name,
                                                 double weight) {
  if (auto r = refuse_if_stopping()) return *r;
  const FacePose* pose = head_.cfg->expressions.find(name);
  if (pose == nullptr) return refuse(404, "no expression '" + name + "' in the library");
  FaceDirector::Pose values = head_.model().neutral;
  pose->blend_into(values, weight);
  log_.add("command", who, "hold expression " + name + " at " + std::to_string(weight));
  director_.hold(FaceDirector::Source::kExpression, name, values);
  return {};
}

HeadService::Result HeadService::hold_pose(const std::string& who, const FaceDirector::Pose& pose,
                                           const std::string& summary) {
  if (auto r = refuse_if_stopping()) return *r;
  log_.add("command", who, "hold pose " + summary);
  director_.hold(FaceDirector::Source::kPose, "", pose);
  return {};
}

}  // namespace facectl
