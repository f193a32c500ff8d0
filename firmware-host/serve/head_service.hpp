#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "control/telemetry_record.hpp"
#include "firmware-host/run/head_runtime.hpp"
#include "firmware-host/serve/event_log.hpp"
#include "firmware-host/serve/face_director.hpp"
#include "firmware-host/serve/show_catalog.hpp"

namespace facectl {

// The operations `facectl serve` offers on a running head, each checked
// against the safety state machine before it is passed on as a request the
// tick may still refuse: nothing here moves an actuator, bypasses a limit,
// the envelope or an e-stop. Also the monitor thread that drains the tick's
// transitions and telemetry for the API and the event log. Never runs on the
// real-time thread; the tick only sees lock-free flags and its mailbox.
class HeadService {
 public:
  // What an operation answered: an HTTP status and, unless 2xx, why.
  struct Result {
    int status = 200;
    std::string error;
  };

  struct ActiveFault {
    std::string state;  // FAULT or ESTOP
    std::string reason;
    std::string detail;
    double time_s = 0.0;
  };

  HeadService(HeadRuntime& head, FaceDirector& director, const ShowCatalog& shows, EventLog& log);
  ~HeadService();
  HeadService(const HeadService&) = delete;
  HeadService& operator=(const HeadService&) = delete;

  void start_monitor();
  void stop_monitor();

  Result enable(const std::string& who);
  Result disable(const std::string& who);
  Result reset(const std::string& who, bool then_enable);
  Result play(const std::string& who, const std::string& show, bool queue);
  Result stop_show(const std::string& who);
  Result hold_expression(const std::string& who, const std::string& name, double weight);
  // `pose`: SI values over neutral for the signals set; checked by the caller.
  Result hold_pose(const std::string& who, const FaceDirector::Pose& pose,
                   const std::string& summary);

  // JOG: from RUNNING and back; one actuator at a time to a position in its
  // YAML unit (deg or mm), inside its soft range.
  Result jog_start(const std::string& who);
  Result jog_stop(const std::string& who);
  Result jog(const std::string& who, const std::string& actuator, double position);

  // SIGTERM: eases the head to rest, and from now on refuses every operation
  // that could move it again (503), so no client can cancel the stop.
  void begin_shutdown(const std::string& who);

  // Where JOG may take an actuator, in its YAML unit: its soft range within
  // the range the static proof found some admissible face maps it to (the
  // envelope and the coupled face limits included; docs/SAFETY.md, "Jog").
  struct JogRange {
    double lo = 0.0, hi = 0.0;
  };
  // Proven on first use, not at start-up: the proof takes most of a second on
  // the default rig, and only jogging and the rig's description need it.
  const std::vector<JogRange>& jog_ranges() const;

  SafetyState state() const { return head_.controller->state(); }
  std::optional<ActiveFault> active_fault() const;
  // The newest telemetry record, and how many the monitor has taken.
  std::uint64_t latest(TelemetryRecord& out) const;
  double uptime_s() const;
  const HeadRuntime& head() const { return head_; }
  const ShowCatalog& shows() const { return shows_; }
  const FaceDirector& director() const { return director_; }
  const EventLog& log() const { return log_; }
  EventLog& log() { return log_; }
  // Set by the monitor: true while the tick count advances (sd_notify WATCHDOG).
  bool loop_alive() const { return loop_alive_.load(std::memory_order_relaxed); }

 private:
  void monitor();
  void drain_events();
  bool wait_for_state_change(SafetyState from, double seconds) const;
  std::optional<Result> refuse_if_stopping() const;

  HeadRuntime& head_;
  FaceDirector& director_;
  const ShowCatalog& shows_;
  EventLog& log_;
  std::int64_t start_ns_;
  std::uint64_t events_lost_said_ = 0;
  mutable std::once_flag jog_proven_;
  mutable std::vector<JogRange> jog_ranges_;  // by actuator index, once proven
  std::atomic<bool> stopping_{false};

  mutable std::mutex mutex_;  // latest_, fault_: between the monitor and the API's threads
  TelemetryRecord latest_{};
  TelemetryRecord newest_{};  // the monitor's own
  std::uint64_t taken_ = 0;
  std::optional<ActiveFault> fault_;

  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> loop_alive_{true};
};

}  // namespace facectl
