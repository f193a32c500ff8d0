#pragma once

#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <optional>
#include <span>

#include "control/actuator_bus.hpp"
#include "control/command/command_sanitizer.hpp"
#include "control/command/command_shaper.hpp"
#include "control/command/face_command.hpp"
#include "control/controller_model.hpp"
#include "control/envelope/face_envelope.hpp"
#include "control/envelope/mandible_envelope.hpp"
#include "control/limits/trajectory_limiter.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "control/realtime/spsc_ring.hpp"
#include "control/safety/safety_state_machine.hpp"
#include "control/telemetry_record.hpp"

namespace facectl {

// Lock-free channels between the tick and the non-real-time threads.
struct ControllerChannels {
  LatestValueMailbox<FaceCommand>* commands = nullptr;  // in: latest face command
  SpscRing<TelemetryRecord>* telemetry = nullptr;       // out: one record per tick (optional)
  SpscRing<TransitionEvent>* events = nullptr;          // out: state transitions (optional)
};

// Timing of one tick, measured by the loop (or simulated offline).
struct TickTiming {
  std::uint64_t tick = 0;
  std::int64_t now_ns = 0;
  double time_s = 0.0;
  double dt_s = 0.0;
  double wake_latency_s = 0.0;
  double compute_s = 0.0;  // previous tick
  int consecutive_overruns = 0;
};

// Counts kept by the tick; read by other threads only after the loop stopped,
// except the atomics.
struct ControllerCounters {
  std::uint64_t ticks = 0;
  std::uint64_t stale_ticks = 0;
  std::uint64_t envelope_clamps = 0;
  std::uint64_t coupled_projections = 0;
  std::array<std::uint64_t, CoupledConstraints::kMaxConstraints> coupled_hits{};
  std::uint64_t actuator_coupled_projections = 0;  // ticks the mapped targets were projected
  std::array<std::uint64_t, CoupledConstraints::kMaxConstraints> actuator_coupled_hits{};
  std::uint64_t actuator_coupled_steps = 0;  // ticks a coupled position bound shaped a step
  std::uint64_t limit_breaches = 0;
  std::array<std::array<std::uint64_t, kLimitFlagCount>, kMaxActuators>
      limit_hits{};  // per LimitFlag bit
};

// The real-time core: one call of tick() runs the tick's steps (sanitise,
// shape, envelope, reduced face model, mapping, limits, safety, buses,
// telemetry; README "Layout") over the const model and this object's preallocated state. tick()
// allocates nothing, takes no lock and makes no blocking call; whatever the
// backends do in read/write must honour the same rules.
class Controller {
 public:
  Controller(const ControllerModel& model, std::span<ActuatorBus* const> buses, SafetyIo& io,
             ControllerChannels channels);

  void tick(const TickTiming& timing);

  // Requests from other threads (signal handlers included): lock-free flags.
  // Enabling again after a shutdown withdraws the shutdown.
  void request_enable() {
    shutdown_request_.store(false, std::memory_order_relaxed);
    enable_request_.store(true, std::memory_order_relaxed);
  }
  void request_shutdown() { shutdown_request_.store(true, std::memory_order_relaxed); }
  void request_reset() { reset_request_.store(true, std::memory_order_relaxed); }
  // JOG (docs/SAFETY.md, "Jog"): entered from RUNNING, left back to it. In
  // JOG the face input is ignored and every actuator holds where JOG found
  // it, except the one jogged: towards its target, clamped to its soft range,
  // at jog_speed_fraction of its max velocity. A strut of the mandible
  // mechanism is never jogged alone (the pose holds).
  void request_jog(bool on) {
    (on ? jog_request_ : jog_end_request_).store(true, std::memory_order_relaxed);
  }
  void request_jog_target(std::size_t actuator, double target) {
    jog_target_.store(pack_jog(static_cast<std::int32_t>(actuator), static_cast<float>(target)),
                      std::memory_order_relaxed);
  }
  // True for the struts of the mandible mechanism, which JOG does not move alone.
  bool is_strut(std::size_t actuator) const { return ((strut_mask_ >> actuator) & 1u) != 0; }

  SafetyState state() const { return state_mirror_.load(std::memory_order_relaxed); }
  std::uint64_t faults_seen() const { return faults_seen_.load(std::memory_order_relaxed); }
  // True if a shutdown disabled the outputs before rest was reached.
  bool stop_timed_out() const { return stop_timed_out_.load(std::memory_order_relaxed); }
  // True while FAULT keeps some actuator commanded (hold or rest).
  bool fault_holding() const { return fault_holding_.load(std::memory_order_relaxed); }
  // True while a held or resting actuator (or the jaw's pose) is still
  // moving: releasing the outputs now would drop it mid-motion.
  bool fault_moving() const { return fault_moving_.load(std::memory_order_relaxed); }
  // Only once the loop has stopped ticking: disables every bus and drops
  // power-enable, since a FAULT hold cannot outlive the loop commanding it.
  void release_outputs();

  const ControllerModel& model() const { return model_; }
  const ControllerCounters& counters() const { return counters_; }
  const CommandSanitizer& sanitizer() const { return sanitizer_; }
  const std::array<double, kMaxFaceSignals>& face() const { return face_; }
  const std::array<double, kMaxActuators>& commands() const { return command_; }
  const std::array<double, kMaxActuators>& measured() const { return measured_; }
  const LimiterState& limiter(std::size_t actuator) const { return limiter_[actuator]; }
  // This tick's intermediate results, for offline checks (facectl verify).
  const std::array<double, kMaxActuators>& mapped() const { return mapped_; }
  const std::array<double, kMaxActuators>& targets() const { return target_; }
  double envelope_excess() const { return envelope_excess_; }  // largest clamp, SI
  std::uint32_t coupled_flags() const { return coupled_flags_; }
  double coupled_violation() const { return coupled_violation_; }
  std::uint32_t actuator_coupled_flags() const { return actuator_coupled_flags_; }
  double actuator_coupled_violation() const { return actuator_coupled_violation_; }
  std::uint64_t mapping_clamps() const { return mapping_clamps_; }
  const std::array<LimitFlags, kMaxActuators>& limit_flags() const { return flags_; }
  // Drive-level protection (docs/SAFETY.md): this tick's health and state.
  const ActuatorHealth& health(std::size_t actuator) const { return health_[actuator]; }
  const ProtectionState& protection(std::size_t actuator) const { return protection_[actuator]; }
  bool input_stale() const { return input_stale_; }

 private:
  void read_inputs(const TickTiming& timing);
  void choose_targets();
  // Drive-level protection (controller_protection.cpp): steps every
  // actuator's state; true while some actuator's protection FAULT is latched.
  bool step_drive_protection(double dt);
  void clear_protection_faults();  // on reset: those whose condition has gone
  bool protected_at(std::size_t i) const {
    return i < model_.protection.size() && model_.protection[i].configured;
  }
  bool hardware_error(std::size_t i) const {
    return protected_at(i) &&
           (health_[i].hardware_error & model_.protection[i].hardware_error_mask) != 0;
  }
  // In FAULT an actuator that its own protection faulted, or whose servo
  // reports a hardware error, relaxes whatever its reaction: holding, or
  // going to a rest that may be where it is pushing (a jaw closing on a
  // finger), would keep the load or heat on.
  bool protection_relaxes(std::size_t i) const {
    return hardware_error(i) || (protected_at(i) && protection_[i].mode == ProtectionMode::kFault);
  }
  bool limit_actuators(double dt, LimitFlags* flags);  // true if the backstop acted
  // Actuator coupled limits as this tick's position bounds (bound_lo_,
  // bound_hi_); returns the bit set of the actuators they bound.
  std::uint64_t bound_actuator_constraints();
  // The mandible mechanism's struts: the pose is limited in its own DOFs and
  // the struts follow it (docs/MANDIBLE_MECHANISM.md, "Moving the struts together").
  void limit_mechanism(double dt, LimitFlags* flags);
  void start_mechanism();  // ENABLING: the pose limiter starts at the measured pose
  std::optional<face::MandiblePose> measured_mandible_pose();
  bool mechanism_out_of_envelope();
  bool measured_in_range(std::size_t i) const;  // inside its hardware range
  bool feedback_out_of_range();
  bool at_rest(double dt);
  void enter_state(SafetyState state, SafetyState from, TransitionReason reason);
  // FAULT with per-actuator reactions (controller_fault_reaction.cpp,
  // docs/SAFETY.md "Fault reaction"): true while some actuator holds or rests.
  bool start_fault_reactions(SafetyState from, TransitionReason reason);
  // A faulted bus, the safety I/O, or feedback out of range: relax.
  void relax_uncommandable(bool io_fault);
  bool relax_split_mechanism();  // true if it relaxed struts
  bool apply_fault_enables();    // false once every actuator relaxed
  bool driving() const { return safety_.outputs_enabled() || fault_driving_; }
  bool relaxed(std::size_t i) const { return fault_driving_ && fault_driven_[i] == 0; }
  bool fault_reaction_moving() const;
  void write_outputs(const TickTime& time);
  void publish_telemetry(const TickTiming& timing, TransitionReason transition,
                         std::uint32_t rejected, std::uint8_t envelope_flags,
                         const LimitFlags* flags);
  std::uint32_t coupled_flags_ = 0;
  double coupled_violation_ = 0.0;
  std::uint32_t actuator_coupled_flags_ = 0;
  double actuator_coupled_violation_ = 0.0;
  double envelope_excess_ = 0.0;
  std::array<LimitFlags, kMaxActuators> flags_{};  // this tick's, per actuator
  std::array<double, kMaxFaceSignals> before_envelope_{};
  void log_transition(const TickTiming& timing, SafetyState from, TransitionReason reason);

  const ControllerModel& model_;
  std::array<ActuatorBus*, kMaxBuses> buses_{};
  std::size_t bus_count_ = 0;
  SafetyIo& io_;
  ControllerChannels channels_;

  CommandSanitizer sanitizer_;
  CommandShaper shaper_;
  FaceEnvelope envelope_;
  SafetyStateMachine safety_;

  FaceCommand command_in_{};
  std::uint64_t last_sequence_ = 0;
  bool ever_received_ = false;
  bool fresh_ = false;
  std::int64_t last_fresh_ns_ = 0;
  bool input_stale_ = true;

  std::array<double, kMaxFaceSignals> face_{};
  MappingWorkspace mapping_ws_;
  std::uint64_t mapping_clamps_ = 0;
  std::array<double, kMaxActuators> bound_lo_{};  // this tick's coupled position bounds
  std::array<double, kMaxActuators> bound_hi_{};
  std::uint64_t strut_mask_ = 0;  // the mandible mechanism's struts, by actuator index
  std::array<double, kMaxActuators> mapped_{};
  std::array<double, kMaxActuators> target_{};
  std::array<double, kMaxActuators> command_{};
  std::array<double, kMaxActuators> measured_{};
  std::array<double, kMaxActuators> enable_start_{};
  std::array<LimiterState, kMaxActuators> limiter_{};
  std::array<LimiterState, 3> pose_limiter_{};  // pitch, yaw, protrusion
  face::MandiblePose pose_start_;               // where ENABLING found the jaw
  MandibleRotations limited_rotations_;         // of the limited pose, reused while an angle holds
  MandibleLinearisation last_measured_;         // warm start of the measured pose's solve

  ControllerCounters counters_;
  std::atomic<bool> enable_request_{false};
  std::atomic<bool> shutdown_request_{false};
  std::atomic<bool> reset_request_{false};
  std::atomic<bool> jog_request_{false};
  std::atomic<bool> jog_end_request_{false};
  // One word, so the actuator and its target never tear: the index in the
  // high half, the target's float bits (1e-7 of a rad or m) in the low one.
  // An integer, not a struct: clang calls libatomic for an atomic struct.
  static std::uint64_t pack_jog(std::int32_t actuator, float target) {
    return (std::uint64_t{static_cast<std::uint32_t>(actuator)} << 32) |
           std::bit_cast<std::uint32_t>(target);
  }
  static constexpr std::uint64_t kNoJog = std::uint64_t{0xFFFFFFFFu} << 32;  // actuator -1
  std::atomic<std::uint64_t> jog_target_{kNoJog};
  std::array<double, kMaxActuators> jog_hold_{};  // JOG: where each actuator holds
  std::size_t jog_active_ = kMaxActuators;        // JOG: the actuator jogged last
  face::MandiblePose jog_pose_;                   // JOG: the pose the mechanism holds
  std::atomic<SafetyState> state_mirror_{SafetyState::kIdle};
  std::atomic<std::uint64_t> faults_seen_{0};
  std::atomic<bool> stop_timed_out_{false};
  std::atomic<bool> fault_holding_{false};
  std::atomic<bool> fault_moving_{false};
  double settled_time_ = 0.0;
  std::array<double, kMaxActuators> settling_{};  // low-passed measured positions in STOPPING
  const char* bus_fault_reason_ = "";
  std::array<bool, kMaxBuses> bus_faulted_{};  // this tick's BusStatus::fault
  bool jaw_out_of_envelope_ = false;           // this tick's mechanism_out_of_envelope()
  // FAULT: which actuators hold or rest (1), where to, and the buses they keep on.
  bool fault_driving_ = false;
  std::array<std::uint8_t, kMaxActuators> fault_driven_{};
  std::array<double, kMaxActuators> fault_target_{};
  face::MandiblePose fault_pose_;
  std::array<bool, kMaxBuses> bus_driven_{};
  // Drive-level protection: the buses' health readings and each actuator's state.
  std::array<ActuatorHealth, kMaxActuators> health_{};
  std::array<ProtectionState, kMaxActuators> protection_{};
  std::size_t protection_faulted_ = kMaxActuators;  // the one named in the event
};

}  // namespace facectl
