#include "control/controller.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>

#include "control/limits/coupled_position_bounds.hpp"
#include "control/units.hpp"

namespace facectl {

Controller::Controller(const ControllerModel& model, std::span<ActuatorBus* const> buses,
                       SafetyIo& io, ControllerChannels channels)
    : model_(model),
      io_(io),
      channels_(channels),
      sanitizer_(model.layout),
      shaper_(model.layout, model.shaping, model.neutral),
      envelope_(model.layout, model.envelope, model.admissible),
      safety_(model.safety),
      mapping_ws_(make_mapping_workspace(model.mapping)) {
  if (buses.size() != model.buses.size() || buses.size() > kMaxBuses) {
    throw std::invalid_argument("controller: one backend per configured bus is required");
  }
  if (channels.commands == nullptr) throw std::invalid_argument("controller: no command mailbox");
  bus_count_ = buses.size();
  std::copy(buses.begin(), buses.end(), buses_.begin());
  sanitizer_.reset(model.neutral);
  face_ = model.neutral;
  last_measured_ = MandibleLinearisation(to_vector(model.mandible_rest));
  if (model.mapping.mechanism) {
    for (std::size_t s = 0; s < model.mapping.mechanism->struts(); ++s) {
      strut_mask_ |= std::uint64_t{1} << model.mapping.mechanism->strut[s].actuator;
    }
  }
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    command_[i] = model.actuators[i].rest;
    measured_[i] = model.actuators[i].rest;
    mapped_[i] = model.actuators[i].rest;
  }
  // IDLE means disabled: make it true of the hardware too, whatever a crashed
  // previous run left enabled.
  for (std::size_t b = 0; b < bus_count_; ++b) buses_[b]->set_enabled(false);
  io_.set_power_enable(false);
}

namespace {

// Bounded copy into a fixed buffer (no formatting machinery in the tick).
void copy_text(char* out, std::size_t size, const char* text) {
  std::size_t i = 0;
  for (; i + 1 < size && text[i] != '\0'; ++i) out[i] = text[i];
  out[i] = '\0';
}

// "N missed deadlines", written without printf.
void write_count(char* out, std::size_t size, int n, const char* suffix) {
  char digits[16];
  int len = 0;
  unsigned v = n < 0 ? 0u : static_cast<unsigned>(n);
  do {
    digits[len++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0 && len < 15);
  std::size_t i = 0;
  while (len > 0 && i + 1 < size) out[i++] = digits[--len];
  out[i] = '\0';
  copy_text(out + i, size - i, suffix);
}

// A reading with one decimal ("73.4"), written without printf.
void write_decimal(char* out, std::size_t size, double v) {
  if (size == 0) return;
  if (!std::isfinite(v) || std::fabs(v) > 2e9) {
    copy_text(out, size, "?");
    return;
  }
  std::size_t i = 0;
  if (v < 0 && i + 1 < size) out[i++] = '-';
  const long tenths = std::lround(std::fabs(v) * 10.0);
  write_count(out + i, size - i, static_cast<int>(tenths / 10), ".");
  i += std::char_traits<char>::length(out + i);
  if (i + 1 < size) {
    out[i++] = static_cast<char>('0' + tenths % 10);
    out[i] = '\0';
  }
}

}  // namespace

void Controller::read_inputs(const TickTiming& timing) {
  // Step 1: the latest face command, if a new one arrived.
  fresh_ = channels_.commands->consume(command_in_) &&
           (!ever_received_ || command_in_.sequence != last_sequence_);
  if (fresh_) {
    last_sequence_ = command_in_.sequence;
    ever_received_ = true;
    last_fresh_ns_ = timing.now_ns;
  }
  input_stale_ = !ever_received_ || static_cast<double>(timing.now_ns - last_fresh_ns_) * 1e-9 >
                                        model_.safety.input_timeout_s;
  if (input_stale_) ++counters_.stale_ticks;

  // Measured positions for bumpless enable and telemetry.
  const TickTime time{timing.now_ns, timing.dt_s};
  for (std::size_t b = 0; b < bus_count_; ++b) {
    const BusModel& bus = model_.buses[b];
    buses_[b]->read(time, std::span<double>(measured_.data() + bus.first, bus.count));
    buses_[b]->read_health(std::span<ActuatorHealth>(health_.data() + bus.first, bus.count));
  }
}

void Controller::choose_targets() {
  // ENABLING blends from where the actuators were to the live target;
  // STOPPING heads for rest whatever the input says (the show is over).
  const SafetyState state = safety_.state();
  const double blend = safety_.enable_blend();
  if (state == SafetyState::kJog) {
    const std::uint64_t jog = jog_target_.load(std::memory_order_relaxed);
    const auto a = static_cast<std::size_t>(jog >> 32);  // -1 (none) is out of range
    const float target = std::bit_cast<float>(static_cast<std::uint32_t>(jog));
    if (a < model_.actuators.size() && !is_strut(a) && std::isfinite(target)) {
      // Another actuator than the last: the last one stops where it is now
      // (the limiter brakes it without passing that point).
      if (jog_active_ < model_.actuators.size() && jog_active_ != a) {
        jog_hold_[jog_active_] = limiter_[jog_active_].position;
      }
      jog_active_ = a;
      const ActuatorLimits& l = model_.actuators[a].limits;
      jog_hold_[a] = std::clamp(static_cast<double>(target), l.soft_min, l.soft_max);
    }
  }
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    double target = mapped_[i];
    if (state == SafetyState::kEnabling) {
      target = enable_start_[i] + blend * (mapped_[i] - enable_start_[i]);
    } else if (state == SafetyState::kJog) {
      target = jog_hold_[i];
    } else if (state == SafetyState::kStopping) {
      target = model_.actuators[i].rest;
    } else if (state == SafetyState::kFault) {
      target = fault_driven_[i] != 0 ? fault_target_[i] : measured_[i];
    }
    // Drive-level protection before the limiter: every limit still holds and
    // the change is rate-limited (docs/SAFETY.md, "Drive-level protection").
    if (protected_at(i)) {
      target = protected_target(model_.protection[i], model_.actuators[i].limits,
                                model_.actuators[i].rest, protection_[i], target);
    }
    target_[i] = target;
  }
}

std::uint64_t Controller::bound_actuator_constraints() {
  // Each actuator's limiter moves on its own, so the joint motion could cut a
  // corner of an actuator coupled limit although both ends are admissible.
  // Instead each limit becomes this tick's position bounds for its actuators'
  // limiters, which never cross them (docs/SAFETY.md, actuator coupled limits).
  // A relaxed actuator is where it is measured: the others keep clear of it.
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    if (relaxed(i)) limiter_[i] = {measured_[i], 0.0, 0.0};
  }
  return coupled_position_bounds(model_.actuator_constraints, model_.actuators.data(),
                                 limiter_.data(), target_.data(), bound_lo_.data(),
                                 bound_hi_.data());
}

void Controller::limit_mechanism(double dt, LimitFlags* flags) {
  // Limiting each strut on its own would bend the jaw's path out of the
  // envelope in a fast move (each strut lags differently). So the pose is
  // limited in pitch, yaw and protrusion, inside the envelope, with rates the
  // model builder proved every strut can follow, and the struts take the
  // strokes of that pose.
  const MandibleMechanism& mech = *model_.mapping.mechanism;
  const SafetyState state = safety_.state();
  face::MandiblePose target{face_[model_.layout.jaw_pitch()], face_[model_.layout.jaw_yaw()],
                            face_[model_.layout.jaw_protrusion()]};
  if (state == SafetyState::kEnabling) {
    const double b = safety_.enable_blend();
    target.pitch_rad = pose_start_.pitch_rad + b * (target.pitch_rad - pose_start_.pitch_rad);
    target.yaw_rad = pose_start_.yaw_rad + b * (target.yaw_rad - pose_start_.yaw_rad);
    target.protrusion_m =
        pose_start_.protrusion_m + b * (target.protrusion_m - pose_start_.protrusion_m);
  } else if (state == SafetyState::kJog) {
    target = jog_pose_;
  } else if (state == SafetyState::kStopping) {
    target = model_.mandible_rest;
  } else if (state == SafetyState::kFault) {
    target = fault_pose_;
  }
  const MandibleVector held = mech.held_in(to_vector(target));
  const double goal[3] = {held[0], held[1], held[2]};
  LimitFlags pose_flags = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    if (!mech.driven[k]) {
      pose_limiter_[k] = {goal[k], 0.0, 0.0};
      continue;
    }
    pose_flags |= limit_step(model_.mandible_limits[k], pose_limiter_[k], goal[k], dt);
  }
  const face::MandiblePose pose{pose_limiter_[0].position, pose_limiter_[1].position,
                                pose_limiter_[2].position};
  MandibleStrokes strokes{};
  const MandibleSolveResult r = solve(mech, pose, strokes, &limited_rotations_);
  for (std::size_t s = 0; s < mech.struts(); ++s) {
    const std::size_t i = mech.strut[s].actuator;
    LimiterState& l = limiter_[i];
    const double v = (strokes[s] - l.position) / dt;
    l = {strokes[s], v, (v - l.velocity) / dt};
    flags[i] = pose_flags | (r.clamped ? kLimitMapping : 0);
    if ((mapping_clamps_ >> i) & 1u) flags[i] |= kLimitMapping;
    command_[i] = strokes[s];
  }
}

void Controller::start_mechanism() {
  const MandibleMechanism& mech = *model_.mapping.mechanism;
  pose_start_ = measured_mandible_pose().value_or(model_.mandible_rest);
  const double here[3] = {pose_start_.pitch_rad, pose_start_.yaw_rad, pose_start_.protrusion_m};
  for (std::size_t k = 0; k < 3; ++k) {
    const ActuatorLimits& l = model_.mandible_limits[k];
    pose_limiter_[k] = {std::clamp(here[k], l.soft_min, l.soft_max), 0.0, 0.0};
  }
  // The struts start where the (clamped) pose puts them: within the noise of
  // where they are, because mechanism_out_of_envelope() refused anything else.
  MandibleStrokes strokes{};
  solve(mech, {pose_limiter_[0].position, pose_limiter_[1].position, pose_limiter_[2].position},
        strokes);
  for (std::size_t s = 0; s < mech.struts(); ++s) {
    const std::size_t i = mech.strut[s].actuator;
    limiter_[i] = {strokes[s], 0.0, 0.0};
    command_[i] = strokes[s];
  }
}

std::optional<face::MandiblePose> Controller::measured_mandible_pose() {
  // Warm-started from the last tick's answer: the struts moved at most a
  // tick's travel, so Newton needs a step or two instead of a solve from rest.
  // From rest again if that fails, so the warm start never changes the answer's
  // existence.
  const MandibleMechanism& mech = *model_.mapping.mechanism;
  MandibleStrokes measured{};
  for (std::size_t s = 0; s < mech.struts(); ++s) measured[s] = measured_[mech.strut[s].actuator];
  // Solved to 10 nm of stroke: a hundred times finer than a strut's encoder
  // resolves, and one Newton step from the warm start instead of two.
  constexpr int kIterations = 30;
  constexpr double kStrokeTolerance = 1e-8;
  auto pose = forward(mech, measured, last_measured_, kIterations, kStrokeTolerance);
  if (!pose) {
    MandibleLinearisation rest(to_vector(model_.mandible_rest));
    pose = forward(mech, measured, rest, kIterations, kStrokeTolerance);
    if (pose) last_measured_ = rest;
  }
  return pose;
}

bool Controller::mechanism_out_of_envelope() {
  // Struts measured at no pose of the mandible, or at one outside the envelope
  // by more than measurement noise: enabling would jump the jaw (or it is
  // jammed or miscalibrated). The state machine refuses to enable on it.
  if (!model_.mapping.mechanism) return false;
  const auto pose = measured_mandible_pose();
  if (!pose) return true;
  constexpr double kAngle = 0.5 * kDeg, kLength = 0.5e-3;
  const MandibleEnvelope& e = model_.envelope;
  return pose->pitch_rad < e.pitch.min - kAngle || pose->pitch_rad > e.pitch.max + kAngle ||
         pose->yaw_rad < e.yaw.min - kAngle || pose->yaw_rad > e.yaw.max + kAngle ||
         pose->protrusion_m < e.protrusion.min - kLength ||
         pose->protrusion_m > e.protrusion.max + kLength;
}

bool Controller::limit_actuators(double dt, LimitFlags* flags) {
  bool breach = false;
  // The struts of a mandible mechanism take the strokes of the limited pose
  // (limit_mechanism): their own steps would be overwritten, so skip them.
  const bool by_pose =
      model_.mapping.mechanism && !relaxed(model_.mapping.mechanism->strut[0].actuator);
  const std::uint64_t coupled =
      model_.actuator_constraints.size() != 0 ? bound_actuator_constraints() : 0;
  bool bounded = false;
  const bool jog = safety_.state() == SafetyState::kJog;
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    if (by_pose && ((strut_mask_ >> i) & 1u) != 0) continue;
    ActuatorLimits l = model_.actuators[i].limits;
    // JOG caps the speed only: braking from a faster motion keeps its full rate.
    if (jog) l.max_velocity *= model_.safety.jog_speed_fraction;
    flags[i] = ((coupled >> i) & 1u) != 0
                   ? limit_step_within(l, limiter_[i], target_[i], dt, bound_lo_[i], bound_hi_[i])
                   : limit_step(l, limiter_[i], target_[i], dt);
    bounded = bounded || (flags[i] & kLimitCoupled) != 0;
    if ((mapping_clamps_ >> i) & 1u) flags[i] |= kLimitMapping;
    command_[i] = limiter_[i].position;
  }
  if (bounded) ++counters_.actuator_coupled_steps;
  if (by_pose) limit_mechanism(dt, flags);
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    const ActuatorLimits& l = model_.actuators[i].limits;
    if (relaxed(i)) {
      // Torque off in FAULT: nothing is commanded; follow the measurement.
      limiter_[i] = {measured_[i], 0.0, 0.0};
      command_[i] = measured_[i];
      flags[i] = 0;
      continue;
    }
    // Independent backstop against the hardware range, NaN included: such a
    // command is never sent, and the state machine faults on it.
    if (!(l.position_min <= command_[i] && command_[i] <= l.position_max)) {
      flags[i] |= kLimitBreach;
      command_[i] = std::isfinite(command_[i])
                        ? std::clamp(command_[i], l.position_min, l.position_max)
                        : std::clamp(measured_[i], l.position_min, l.position_max);
      limiter_[i] = {command_[i], 0.0, 0.0};
      breach = true;
      ++counters_.limit_breaches;
    }
    // Visit only the set bits: most ticks set none.
    for (unsigned bits = flags[i] & ((1u << kLimitFlagCount) - 1u); bits != 0; bits &= bits - 1) {
      ++counters_.limit_hits[i][static_cast<std::size_t>(std::countr_zero(bits))];
    }
  }
  return breach;
}

bool Controller::measured_in_range(std::size_t i) const {
  const ActuatorLimits& l = model_.actuators[i].limits;
  return l.position_min <= measured_[i] && measured_[i] <= l.position_max;
}

bool Controller::feedback_out_of_range() {
  bool out = false;
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) out = out || !measured_in_range(i);
  // Every tick, also when an actuator is already out: FAULT's reactions read it.
  jaw_out_of_envelope_ = mechanism_out_of_envelope();
  return out || jaw_out_of_envelope_;
}

bool Controller::at_rest(double dt) {
  // Both the command and the measured position must have settled at rest,
  // and stayed there, before outputs drop: a jaw or neck under gravity is
  // not let go while it is still moving.
  // Measurements carry noise: judge a low-passed position (20 ms), so that
  // noise does not keep a settled actuator "moving" forever.
  const double alpha = 1.0 - std::exp(-dt / 0.02);
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    settling_[i] += alpha * (measured_[i] - settling_[i]);
  }
  bool settled = true;
  for (std::size_t i = 0; i < model_.actuators.size() && settled; ++i) {
    const ActuatorLimits& l = model_.actuators[i].limits;
    const double range = l.soft_max - l.soft_min;
    const double rest = model_.actuators[i].rest;
    settled = std::fabs(limiter_[i].position - rest) <= model_.rest_tolerance_fraction * range &&
              std::fabs(limiter_[i].velocity) <= 0.01 * l.max_velocity &&
              std::fabs(settling_[i] - rest) <= model_.rest_measured_tolerance_fraction * range;
  }
  settled_time_ = settled ? settled_time_ + dt : 0.0;
  return settled_time_ >= model_.rest_dwell_s;
}

void Controller::enter_state(SafetyState state, SafetyState from, TransitionReason reason) {
  const bool outputs = commands_actuators(state);
  if (state == SafetyState::kEnabling && from == SafetyState::kJog) {
    // Leaving JOG: the outputs are live and the limiters keep their motion;
    // the ramp starts from the commands and the held pose as they are.
    std::copy_n(command_.begin(), model_.actuators.size(), enable_start_.begin());
    pose_start_ = jog_pose_;
  } else if (state == SafetyState::kEnabling) {
    // Bumpless: the commanded trajectory starts where the actuators are
    // (inside their hardware range: the state machine refused otherwise), and
    // the backends hold there until the first write (ActuatorBus::set_enabled).
    for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
      const ActuatorLimits& l = model_.actuators[i].limits;
      const double here = std::clamp(measured_[i], l.position_min, l.position_max);
      enable_start_[i] = std::clamp(here, l.soft_min, l.soft_max);
      limiter_[i] = {here, 0.0, 0.0};
      command_[i] = here;
    }
    if (model_.mapping.mechanism) start_mechanism();
    settled_time_ = 0.0;
  }
  fault_driving_ = state == SafetyState::kFault && start_fault_reactions(from, reason);
  if (!outputs && !fault_driving_) {
    for (std::size_t b = 0; b < bus_count_; ++b) buses_[b]->set_enabled(false);
    io_.set_power_enable(false);
  } else if (state == SafetyState::kEnabling && !commands_actuators(from)) {
    // (From JOG the outputs are live already: only the ramp starts again.)
    io_.set_power_enable(true);
    for (std::size_t b = 0; b < bus_count_; ++b) buses_[b]->set_enabled(true);
  }
  if (state == SafetyState::kFault || state == SafetyState::kEstop) {
    faults_seen_.fetch_add(1, std::memory_order_relaxed);
  }
  if (state == SafetyState::kJog) {
    // Hold where JOG found everything; no jog target until one is asked for.
    std::copy_n(command_.begin(), model_.actuators.size(), jog_hold_.begin());
    jog_pose_ = {pose_limiter_[0].position, pose_limiter_[1].position, pose_limiter_[2].position};
    jog_target_.store(kNoJog, std::memory_order_relaxed);
    jog_active_ = kMaxActuators;
  }
  if (state == SafetyState::kStopping) {
    settled_time_ = 0.0;
    std::copy_n(measured_.begin(), model_.actuators.size(), settling_.begin());
  }
  state_mirror_.store(state, std::memory_order_relaxed);
}

void Controller::write_outputs(const TickTime& time) {
  // Nothing is transmitted in IDLE or ESTOP, nor in FAULT but to the buses of
  // actuators that hold or rest.
  if (!driving()) return;
  for (std::size_t b = 0; b < bus_count_; ++b) {
    if (!safety_.outputs_enabled() && !bus_driven_[b]) continue;
    const BusModel& bus = model_.buses[b];
    buses_[b]->write(time, std::span<const double>(command_.data() + bus.first, bus.count));
  }
}

void Controller::log_transition(const TickTiming& timing, SafetyState from,
                                TransitionReason reason) {
  if (channels_.events == nullptr) return;
  TransitionEvent* ev = channels_.events->begin_push();
  if (ev == nullptr) return;  // counted by the ring as a drop
  ev->tick = timing.tick;
  ev->time_s = timing.time_s;
  ev->from = from;
  ev->to = safety_.state();
  ev->reason = reason;
  ev->detail[0] = '\0';
  if (reason == TransitionReason::kBusFault) {
    copy_text(ev->detail, sizeof ev->detail, bus_fault_reason_);
  } else if (reason == TransitionReason::kOverrunStorm) {
    write_count(ev->detail, sizeof ev->detail, timing.consecutive_overruns, " missed deadlines");
  } else if (reason == TransitionReason::kDriveProtection &&
             protection_faulted_ < model_.actuators.size()) {
    const ProtectionState& p = protection_[protection_faulted_];
    const auto& text = model_.protection[protection_faulted_].fault_text;
    copy_text(ev->detail, sizeof ev->detail, text[static_cast<std::size_t>(p.cause)].c_str());
    const std::size_t used = std::char_traits<char>::length(ev->detail);
    write_decimal(ev->detail + used, sizeof ev->detail - used, p.value_at_fault);
  } else if (reason == TransitionReason::kStopTimeout) {
    stop_timed_out_.store(true, std::memory_order_relaxed);
  }
  channels_.events->commit_push();
}

void Controller::publish_telemetry(const TickTiming& timing, TransitionReason transition,
                                   std::uint32_t rejected, std::uint8_t envelope_flags,
                                   const LimitFlags* flags) {
  if (channels_.telemetry == nullptr) return;
  TelemetryRecord* rec = channels_.telemetry->begin_push();
  if (rec == nullptr) return;  // the ring counts the drop; the writer reports it
  rec->tick = timing.tick;
  rec->time_s = timing.time_s;
  rec->dt_s = timing.dt_s;
  rec->wake_latency_s = timing.wake_latency_s;
  rec->compute_s = timing.compute_s;
  rec->state = safety_.state();
  rec->transition = transition;
  rec->input_stale = input_stale_;
  rec->envelope_flags = envelope_flags;
  rec->coupled_flags = coupled_flags_;
  rec->coupled_violation = coupled_violation_;
  rec->actuator_coupled_flags = actuator_coupled_flags_;
  rec->actuator_coupled_violation = actuator_coupled_violation_;
  rec->rejected_values = rejected;
  rec->overruns = static_cast<std::uint32_t>(timing.consecutive_overruns);
  rec->signal_count = static_cast<std::uint16_t>(model_.layout.size());
  rec->actuator_count = static_cast<std::uint16_t>(model_.actuators.size());
  std::copy_n(face_.begin(), model_.layout.size(), rec->face.begin());
  const std::size_t n = model_.actuators.size();
  std::copy_n(command_.begin(), n, rec->command.begin());
  std::copy_n(measured_.begin(), n, rec->feedback.begin());
  std::copy_n(flags, n, rec->limits.begin());
  rec->protected_mask = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!protected_at(i)) continue;
    rec->protected_mask |= std::uint64_t{1} << i;
    const ActuatorHealth& h = health_[i];
    const ProtectionState& p = protection_[i];
    rec->temperature_c[i] = static_cast<float>(h.temperature_c);
    rec->load[i] = static_cast<float>(h.load);
    rec->current_a[i] = static_cast<float>(h.current_a);
    rec->voltage_v[i] = static_cast<float>(h.voltage_v);
    rec->hardware_error[i] = h.hardware_error;
    rec->derate[i] = static_cast<float>(p.factor);
    rec->extreme_s[i] = static_cast<float>(p.in_band_s);
    rec->protection[i] = static_cast<std::uint8_t>(p.mode);
  }
  channels_.telemetry->commit_push();
}

void Controller::tick(const TickTiming& timing) {
  const double dt = timing.dt_s;
  ++counters_.ticks;

  // 1. Read the face command (and the measured positions).
  read_inputs(timing);
  const bool protection_fault = step_drive_protection(dt);
  // 2. Sanitise: bad values are rejected, the last good value held.
  std::uint32_t rejected = 0;
  if (fresh_) rejected = sanitizer_.apply(command_in_);
  // 3. Shape: neutral blend on stale input, activation dynamics, smoothing.
  //    (Only the layout's signals: the whole array is 768 bytes.)
  const auto& shaped = shaper_.apply(sanitizer_.values(), input_stale_, dt);
  std::copy_n(shaped.begin(), model_.layout.size(), face_.begin());
  // 4. Face envelope: mandible limits and admissible rigid ranges.
  std::copy_n(face_.begin(), model_.layout.size(), before_envelope_.begin());
  const std::uint8_t envelope_flags = envelope_.apply(face_);
  envelope_excess_ = 0.0;
  if (envelope_flags != 0) {
    ++counters_.envelope_clamps;
    for (std::size_t i = 0; i < model_.layout.size(); ++i) {
      envelope_excess_ = std::max(envelope_excess_, std::fabs(face_[i] - before_envelope_[i]));
    }
  }
  //    Coupled face limits: a deterministic, bounded projection.
  coupled_flags_ = model_.face_constraints.project(face_.data(), &coupled_violation_);
  if (coupled_flags_ != 0) {
    ++counters_.coupled_projections;
    for (std::size_t c = 0; c < model_.face_constraints.size(); ++c) {
      if ((coupled_flags_ & (1u << c)) != 0) ++counters_.coupled_hits[c];
    }
  }
  // 5-6. Reduced face model (control points), then the rig mapping.
  mapping_clamps_ = map_to_actuators(model_.mapping, mapping_ws_, face_, mapped_);
  //    Actuator coupled limits on the mapped targets (rest is admissible).
  actuator_coupled_flags_ = 0;
  actuator_coupled_violation_ = 0.0;
  if (model_.actuator_constraints.size() != 0) {
    actuator_coupled_flags_ =
        model_.actuator_constraints.project(mapped_.data(), &actuator_coupled_violation_);
    if (actuator_coupled_flags_ != 0) {
      ++counters_.actuator_coupled_projections;
      for (std::size_t c = 0; c < model_.actuator_constraints.size(); ++c) {
        if ((actuator_coupled_flags_ & (1u << c)) != 0) ++counters_.actuator_coupled_hits[c];
      }
    }
  }
  // 7. Actuator limits, only while outputs are live.
  std::fill_n(flags_.begin(), model_.actuators.size(), LimitFlags{0});
  bool breach = false;
  if (driving()) {
    choose_targets();
    breach = limit_actuators(dt, flags_.data());
  }

  // 8. Safety state machine.
  SafetyInputs in;
  in.estop = io_.estop_active();
  in.io_fault = io_.fault();
  in.limit_breach = breach;
  in.feedback_out_of_range = feedback_out_of_range();
  for (std::size_t b = 0; b < bus_count_; ++b) {
    const BusStatus st = buses_[b]->status();
    bus_faulted_[b] = st.fault;
    if (st.fault && !in.bus_fault) {
      in.bus_fault = true;
      bus_fault_reason_ = st.reason;
    }
  }
  in.consecutive_overruns = timing.consecutive_overruns;
  in.enable_request = enable_request_.exchange(false, std::memory_order_relaxed);
  in.shutdown_request = shutdown_request_.load(std::memory_order_relaxed);
  in.reset_request = reset_request_.exchange(false, std::memory_order_relaxed);
  in.drive_protection_fault = protection_fault;
  if (in.reset_request && safety_.state() == SafetyState::kFault) {
    clear_protection_faults();
    in.drive_protection_fault = protection_faulted_ < model_.actuators.size();
  }
  in.jog_request = jog_request_.exchange(false, std::memory_order_relaxed);
  in.jog_end_request = jog_end_request_.exchange(false, std::memory_order_relaxed);
  in.at_rest = safety_.state() == SafetyState::kStopping && at_rest(dt);
  const SafetyState before = safety_.state();
  const TransitionReason transition = safety_.step(in, dt);
  const TickTime time{timing.now_ns, dt};
  if (transition != TransitionReason::kNone) {
    enter_state(safety_.state(), before, transition);
    log_transition(timing, before, transition);
  } else if (fault_driving_) {
    relax_uncommandable(in.io_fault);
  }
  fault_holding_.store(fault_driving_, std::memory_order_relaxed);
  fault_moving_.store(fault_driving_ && fault_reaction_moving(), std::memory_order_relaxed);
  // Telemetry shows where the hardware is while nothing is commanded.
  for (std::size_t i = 0; i < model_.actuators.size(); ++i) {
    if (!driving() || relaxed(i)) command_[i] = measured_[i];
  }

  // 9-10. Encode and write through the drivers (encoding lives in each backend).
  write_outputs(time);
  // 11. Telemetry.
  publish_telemetry(timing, transition, rejected, envelope_flags, flags_.data());
}

}  // namespace facectl
