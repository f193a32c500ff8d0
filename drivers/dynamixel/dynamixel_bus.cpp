#include "drivers/dynamixel/dynamixel_bus.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "control/clock.hpp"
#include "control/realtime/atomic_max.hpp"
#include "drivers/dynamixel/dynamixel_link.hpp"
#include "drivers/protocol/dynamixel2_packet.hpp"

namespace facectl {

namespace {

constexpr std::size_t kStatusOverhead = 11;  // header, id, length, 0x55, error, CRC

std::int64_t seconds_ns(double s) {
  return static_cast<std::int64_t>(std::llround(s * 1e9));
}

// The servo's Hardware Error Status bits, worst first: the one a FAULT names.
constexpr std::uint8_t kErrorOrder[] = {dxl_x::kErrElectricalShock, dxl_x::kErrOverheating,
                                        dxl_x::kErrOverload, dxl_x::kErrMotorEncoder,
                                        dxl_x::kErrInputVoltage};
constexpr std::size_t kErrorReasons = std::size(kErrorOrder) + 1;  // + "other bits"

}  // namespace

struct DynamixelBus::Servo {
  std::uint8_t id = 0;
  std::size_t index = 0;  // actuator index in this bus
  WireEncoding encoding;
  std::int32_t min_pulse = 0;  // the rig's hard limits, in the servo's pulses
  std::int32_t max_pulse = 0;
  // I/O thread only.
  Stage stage = Stage::kSetUp;
  std::int64_t last_ok_ns = 0;
  std::int32_t present = 0;  // pulses
  std::int32_t hold = 0;     // goal while no command newer than the torque-on
  std::uint32_t on_epoch = 0;
  bool answered = false;  // in this cycle's sync read
  bool alert = false;     // a status packet had the alert bit: read Hardware Error Status
  bool hardware_fault = false;
  bool off_pending = false;  // torque off not yet confirmed: sent again each cycle
  // Switched off by a fault, a silence or a lost port: not switched on again
  // until the controller has disabled it (a new enable, not a resumed one).
  bool latched = false;
  std::uint32_t latched_disables = 0;
  double current_unit_a = 0.0;  // per count of Present Current; 0: Present Load
  // Static reasons (BusStatus::reason must outlive the call).
  std::string silent, not_x, refused, watchdog, hardware[kErrorReasons];
  // Shared with the tick.
  std::atomic<const char*> reason{nullptr};
  std::atomic<bool> wanted{false};
  std::atomic<std::uint32_t> disables{0};  // falling edges of `wanted`, from the tick
  std::atomic<bool> on{false};
  std::atomic<bool> ready{false};
};

DynamixelBus::DynamixelBus(std::string name, std::string device, long baud,
                           const std::vector<ActuatorModel>& actuators,
                           const std::vector<double>& initial_positions, DynamixelOptions options)
    : name_(std::move(name)),
      device_(std::move(device)),
      baud_(baud),
      options_(options),
      count_(actuators.size()) {
  const auto refuse = [&](const std::string& what) {
    throw std::invalid_argument("bus " + name_ + ": " + what);
  };
  if (count_ > kMaxActuators) {
    refuse(std::to_string(count_) + " servos, at most " + std::to_string(kMaxActuators));
  }
  if (initial_positions.size() != count_) refuse("one initial position per actuator");
  if (baud_ <= 0) refuse("baud " + std::to_string(baud_));
  if (options_.response_timeout_s <= 0.0 || options_.cycle_period_s <= 0.0 ||
      options_.fault_after_s <= options_.response_timeout_s || options_.return_delay_us < 0 ||
      options_.return_delay_us > 508 || options_.bus_watchdog_ms < 0 ||
      options_.bus_watchdog_ms > 127 * dxl_x::kBusWatchdogUnitMs) {
    refuse("invalid Dynamixel timing");
  }
  for (std::size_t i = 0; i < count_; ++i) {
    const ActuatorModel& a = actuators[i];
    if (a.address < 0 || a.address > dxl2::kMaxId) {
      refuse("actuator " + a.name + ": servo ID " + std::to_string(a.address) + ", expected 0.." +
             std::to_string(dxl2::kMaxId));
    }
    for (const auto& other : servos_) {
      if (other->id == a.address) {
        refuse("actuators " + actuators[other->index].name + " and " + a.name + " share servo ID " +
               std::to_string(a.address));
      }
    }
    auto s = std::make_unique<Servo>();
    s->id = static_cast<std::uint8_t>(a.address);
    s->index = i;
    s->encoding = WireEncoding(a.kind, a.encoding);
    const std::int64_t lo = s->encoding.encode(a.limits.position_min);
    const std::int64_t hi = s->encoding.encode(a.limits.position_max);
    s->min_pulse = static_cast<std::int32_t>(std::min(lo, hi));
    s->max_pulse = static_cast<std::int32_t>(std::max(lo, hi));
    // Position control mode turns within one revolution: 0..4095 pulses.
    if (s->min_pulse < 0 || s->max_pulse > 4095) {
      refuse("actuator " + a.name + ": its hard limits are pulses " + std::to_string(s->min_pulse) +
             ".." + std::to_string(s->max_pulse) +
             ", outside the 0..4095 of an X-series servo in position control (check encoding)");
    }
    const std::string who = name_ + " servo " + std::to_string(a.address) + " (" + a.name + ")";
    s->silent = who + ": not answering within " +
                std::to_string(std::lround(options_.fault_after_s * 1e3)) + " ms";
    s->not_x = who + ": not an X-series servo (its Model Number is not one facectl knows)";
    s->refused = who + ": refused its set-up (a write came back with an error)";
    s->watchdog = who +
                  ": its Bus Watchdog tripped (no instruction for watchdog_ms): it stopped and "
                  "refuses goals";
    for (std::size_t k = 0; k < kErrorReasons; ++k) {
      const std::string bits =
          k < std::size(kErrorOrder) ? dxl_x::hardware_error_text(kErrorOrder[k]) : "other bits";
      s->hardware[k] =
          who + ": hardware error: " + bits + " (torque off; power-cycle or REBOOT the servo)";
    }
    last_feedback_.positions[i] = initial_positions[i];
    servos_.push_back(std::move(s));
  }
  port_lost_ = name_ + ": serial port " + device_ + " lost or cannot be opened";
  measured_ = last_feedback_;
  tx_.resize(dxl2::max_packet_size(4 + count_ * 5));
  const std::int64_t now = monotonic_ns();
  for (auto& s : servos_) s->last_ok_ns = now;  // the silence runs from start-up
  thread_ = std::thread([this] { io_loop(); });
}

DynamixelBus::~DynamixelBus() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  if (link_) {
    // Torque off on the way out, whatever the controller did: one broadcast
    // sync write, which no servo answers.
    std::vector<std::uint8_t> ids, zeros(count_, 0);
    for (const auto& s : servos_) ids.push_back(s->id);
    const std::size_t n = dxl2::encode_sync_write(dxl_x::kTorqueEnable, 1, ids, zeros, tx_);
    if (n > 0) link_->send({tx_.data(), n}, seconds_ns(0.05));
  }
}

// Tick side: mailboxes and atomics only.

void DynamixelBus::read(const TickTime& /*time*/, std::span<double> positions) {
  feedback_.consume(last_feedback_);
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    positions[i] = last_feedback_.positions[i];
  }
}

void DynamixelBus::read_health(std::span<ActuatorHealth> health) {
  feedback_.consume(last_feedback_);
  for (std::size_t i = 0; i < count_ && i < health.size(); ++i) {
    health[i] = last_feedback_.health[i];
  }
}

void DynamixelBus::write(const TickTime& /*time*/, std::span<const double> positions) {
  if (!enabled_.load(std::memory_order_relaxed)) return;
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    staging_.positions[i] = positions[i];
  }
  staging_.epoch = epoch_.load(std::memory_order_relaxed);
  commands_.publish(staging_);
}

void DynamixelBus::set_enabled(bool enabled) {
  // A new epoch before any servo is wanted: the I/O thread reads `wanted`
  // first, so a servo switched on never takes a command written before.
  if (enabled && !enabled_.load(std::memory_order_relaxed)) {
    epoch_.fetch_add(1, std::memory_order_release);
  }
  for (auto& s : servos_) {
    if (!enabled && s->wanted.load(std::memory_order_relaxed)) {
      s->disables.fetch_add(1, std::memory_order_release);
    }
    s->wanted.store(enabled, std::memory_order_release);
  }
  enabled_.store(enabled, std::memory_order_release);
}

void DynamixelBus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  bool any = false;
  bool rising = false;
  for (auto& s : servos_) {
    const bool on = s->index < enabled.size() && enabled[s->index] != 0;
    any = any || on;
    rising = rising || (on && !s->wanted.load(std::memory_order_relaxed));
  }
  // Torque is per servo: each flag is honoured as it is.
  if (rising) epoch_.fetch_add(1, std::memory_order_release);
  for (auto& s : servos_) {
    const bool on = s->index < enabled.size() && enabled[s->index] != 0;
    if (!on && s->wanted.load(std::memory_order_relaxed)) {
      s->disables.fetch_add(1, std::memory_order_release);
    }
    s->wanted.store(on, std::memory_order_release);
  }
  enabled_.store(any, std::memory_order_release);
}

BusStatus DynamixelBus::status() const {
  BusStatus st;
  if (const char* r = port_reason_.load(std::memory_order_acquire)) {
    st.fault = true;
    st.reason = r;
  }
  for (const auto& s : servos_) {
    const char* r = s->reason.load(std::memory_order_acquire);
    if (r != nullptr && !st.fault) {
      st.fault = true;
      st.reason = r;
    }
  }
  st.frames_sent = stats_.cycles.load(std::memory_order_relaxed);
  st.errors = stats_.timeouts.load(std::memory_order_relaxed) +
              stats_.bad_crc.load(std::memory_order_relaxed) +
              stats_.bad_packets.load(std::memory_order_relaxed);
  return st;
}

bool DynamixelBus::ready() const {
  return std::all_of(servos_.begin(), servos_.end(),
                     [](const auto& s) { return s->ready.load(std::memory_order_acquire); });
}

bool DynamixelBus::torque_on(std::size_t actuator) const {
  return actuator < servos_.size() && servos_[actuator]->on.load(std::memory_order_acquire);
}

DynamixelStats DynamixelBus::stats() const {
  DynamixelStats s;
  s.cycles = stats_.cycles.load(std::memory_order_relaxed);
  s.status_packets = stats_.status_packets.load(std::memory_order_relaxed);
  s.timeouts = stats_.timeouts.load(std::memory_order_relaxed);
  s.bad_crc = stats_.bad_crc.load(std::memory_order_relaxed);
  s.bad_packets = stats_.bad_packets.load(std::memory_order_relaxed);
  s.reopens = stats_.reopens.load(std::memory_order_relaxed);
  s.max_cycle_ns = stats_.max_cycle_ns.load(std::memory_order_relaxed);
  return s;
}

// I/O thread.

void DynamixelBus::io_loop() {
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  const std::int64_t period = seconds_ns(options_.cycle_period_s);
  while (!stop_.load(std::memory_order_acquire)) {
    const std::int64_t start = monotonic_ns();
    if (open_port(start)) run_cycle(start);
    publish_counters();
    stats_.cycles.fetch_add(1, std::memory_order_relaxed);
    atomic_max(stats_.max_cycle_ns, static_cast<std::uint64_t>(monotonic_ns() - start));
    feedback_.publish(measured_);
    std::int64_t t = next.tv_sec * 1'000'000'000LL + next.tv_nsec + period;
    if (t < monotonic_ns()) t = monotonic_ns();  // overran: no burst of catch-up cycles
    next.tv_sec = t / 1'000'000'000;
    next.tv_nsec = t % 1'000'000'000;
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
  }
}

bool DynamixelBus::open_port(std::int64_t now_ns) {
  if (link_) return true;
  if (now_ns - last_open_attempt_ns_ < seconds_ns(options_.reconnect_interval_s)) return false;
  const bool reopening = last_open_attempt_ns_ > 0;
  last_open_attempt_ns_ = now_ns;
  try {
    link_ = std::make_unique<DynamixelLink>(device_, baud_);
  } catch (const std::runtime_error&) {
    port_reason_.store(port_lost_.c_str(), std::memory_order_release);
    return false;
  }
  if (reopening) stats_.reopens.fetch_add(1, std::memory_order_relaxed);
  port_reason_.store(nullptr, std::memory_order_release);
  for (auto& s : servos_) s->stage = Stage::kSetUp;  // a new port: every servo again
  return true;
}

void DynamixelBus::lose_port(const char* reason) {
  publish_counters();
  const DynamixelLink::Counters& c = link_->counters();
  counted_.status_packets += c.status_packets;
  counted_.timeouts += c.timeouts;
  counted_.bad_crc += c.bad_crc;
  counted_.bad_packets += c.bad_packets;
  link_.reset();
  port_reason_.store(reason, std::memory_order_release);
  for (auto& s : servos_) {
    if (s->stage == Stage::kOn || s->wanted.load(std::memory_order_acquire)) latch_off(*s);
    s->stage = Stage::kSetUp;
    s->on.store(false, std::memory_order_release);
    s->ready.store(false, std::memory_order_release);
  }
}

void DynamixelBus::publish_counters() {
  if (!link_) return;
  const DynamixelLink::Counters& c = link_->counters();
  stats_.status_packets.store(counted_.status_packets + c.status_packets,
                              std::memory_order_relaxed);
  stats_.timeouts.store(counted_.timeouts + c.timeouts, std::memory_order_relaxed);
  stats_.bad_crc.store(counted_.bad_crc + c.bad_crc, std::memory_order_relaxed);
  stats_.bad_packets.store(counted_.bad_packets + c.bad_packets, std::memory_order_relaxed);
}

void DynamixelBus::fail(Servo& s, const char* reason) {
  s.reason.store(reason, std::memory_order_release);
}

void DynamixelBus::run_cycle(std::int64_t now_ns) {
  Command fresh;
  if (commands_.consume(fresh)) current_ = fresh;
  for (auto& sp : servos_) {
    Servo& s = *sp;
    if (!link_) return;
    if (s.stage == Stage::kSetUp) {
      if (set_up(s)) {
        s.stage = Stage::kReady;
        s.ready.store(true, std::memory_order_release);
      } else if (now_ns - s.last_ok_ns > seconds_ns(options_.fault_after_s) &&
                 s.reason.load(std::memory_order_relaxed) == nullptr) {
        fail(s, s.silent.c_str());
      }
      continue;
    }
    const bool wanted = s.wanted.load(std::memory_order_acquire);
    if (s.latched &&
        (!wanted || s.disables.load(std::memory_order_acquire) != s.latched_disables)) {
      s.latched = false;  // the controller has disabled it since
    }
    const bool want = wanted && !s.hardware_fault && !s.latched;
    if (want && s.stage == Stage::kReady && !s.off_pending) {
      switch_torque(s, true);
    } else if ((!want && s.stage == Stage::kOn) || s.off_pending) {
      switch_torque(s, false);
    }
  }
  if (!link_) return;
  sync_write_goals();
  if (!link_) return;
  sync_read_feedback(now_ns);
  for (auto& sp : servos_) {
    if (link_ && sp->alert) check_hardware_error(*sp);
  }
  if (link_) check_bus_watchdog();
}

void DynamixelBus::latch_off(Servo& s) {
  if (!s.latched) s.latched_disables = s.disables.load(std::memory_order_acquire);
  s.latched = true;
}

// One servo with torque on a cycle, in turn: a tripped Bus Watchdog (-1)
// refuses every goal without a word, so it is looked for.
void DynamixelBus::check_bus_watchdog() {
  if (options_.bus_watchdog_ms == 0 || servos_.empty()) return;
  for (std::size_t k = 0; k < servos_.size(); ++k) {
    watchdog_turn_ = (watchdog_turn_ + 1) % servos_.size();
    Servo& s = *servos_[watchdog_turn_];
    if (s.stage != Stage::kOn) continue;
    std::uint8_t value = 0;
    if (read_register(s, dxl_x::kBusWatchdog, {&value, 1}) && value == 0xFF) {
      fail(s, s.watchdog.c_str());
      switch_torque(s, false);  // and 0 clears the trip
      latch_off(s);
    }
    return;
  }
}

bool DynamixelBus::set_up(Servo& s) {
  std::uint8_t b[8];
  // PING answers at every Status Return Level; then level 2, so that every
  // write is confirmed (the write of it may itself go unanswered).
  const std::size_t n = dxl2::encode_instruction(s.id, dxl2::kPing, {}, tx_);
  if (!transact(s, {tx_.data(), n}, {b, 3})) return false;
  const dxl_x::Model* model = dxl_x::find_model(dxl_x::get_u16(b));
  if (model == nullptr) {
    fail(s, s.not_x.c_str());
    return false;
  }
  s.current_unit_a = model->load == dxl_x::LoadUnit::kCurrent ? model->current_ma * 1e-3 : 0.0;
  if (!read_register(s, dxl_x::kStatusReturnLevel, {b, 1})) {
    b[0] = 0;  // level 0 answers nothing but PING: set it and read again
  }
  if (b[0] != 2) {
    const std::uint8_t level = 2;
    write_register(s, dxl_x::kStatusReturnLevel, {&level, 1});
    if (!read_register(s, dxl_x::kStatusReturnLevel, {b, 1}) || b[0] != 2) return false;
  }
  const std::uint8_t zero = 0;
  // Torque off before any EEPROM write; Bus Watchdog 0 clears a tripped one.
  bool ok = write_register(s, dxl_x::kTorqueEnable, {&zero, 1}) &&
            write_register(s, dxl_x::kBusWatchdog, {&zero, 1});
  ok = ok && read_register(s, dxl_x::kReturnDelayTime, {b, 3});
  if (!ok) return false;
  const auto delay = static_cast<std::uint8_t>(options_.return_delay_us / 2);
  if (b[0] != delay) ok = write_register(s, dxl_x::kReturnDelayTime, {&delay, 1});
  if (ok && b[2] != dxl_x::kPositionControlMode) {
    const std::uint8_t mode = dxl_x::kPositionControlMode;
    ok = write_register(s, dxl_x::kOperatingMode, {&mode, 1});
  }
  if (ok && options_.write_position_limits) {
    std::uint8_t want[8];
    dxl_x::put_i32(want, s.max_pulse);
    dxl_x::put_i32(want + 4, s.min_pulse);
    ok = read_register(s, dxl_x::kMaxPositionLimit, {b, 8});
    if (ok && std::memcmp(b, want, 8) != 0) ok = write_register(s, dxl_x::kMaxPositionLimit, want);
  }
  if (!ok) {
    if (s.reason.load(std::memory_order_relaxed) == nullptr) fail(s, s.refused.c_str());
    return false;
  }
  if (!read_register(s, dxl_x::kHardwareErrorStatus, {b, 1})) return false;
  measured_.health[s.index].hardware_error = b[0];
  if (b[0] != 0) {
    s.alert = true;
    check_hardware_error(s);
    return false;
  }
  if (!read_register(s, dxl_x::kPresentPosition, {b, 4})) return false;
  s.present = dxl_x::get_i32(b);
  measured_.positions[s.index] = s.encoding.decode(s.present);
  s.hardware_fault = false;
  s.reason.store(nullptr, std::memory_order_release);
  return true;
}

bool DynamixelBus::switch_torque(Servo& s, bool on) {
  const std::uint8_t zero = 0;
  if (on) {
    // Bumpless: the goal is where the servo is before the torque comes on,
    // and stays there until the tick writes after this enable.
    std::uint8_t b[4];
    s.hold = s.present;
    s.on_epoch = epoch_.load(std::memory_order_acquire);
    dxl_x::put_i32(b, s.hold);
    const std::uint8_t one = 1;
    const auto watchdog = static_cast<std::uint8_t>(
        (options_.bus_watchdog_ms + dxl_x::kBusWatchdogUnitMs - 1) / dxl_x::kBusWatchdogUnitMs);
    if (!write_register(s, dxl_x::kGoalPosition, {b, 4})) return false;
    // From the torque write on, the servo may be on: any failure after it
    // switches it off again (and retries that until confirmed).
    s.stage = Stage::kOn;
    s.on.store(true, std::memory_order_release);
    if (write_register(s, dxl_x::kTorqueEnable, {&one, 1}) &&
        (watchdog == 0 || write_register(s, dxl_x::kBusWatchdog, {&watchdog, 1}))) {
      return true;
    }
    switch_torque(s, false);
    return false;
  }
  s.stage = s.stage == Stage::kSetUp ? Stage::kSetUp : Stage::kReady;
  s.on.store(false, std::memory_order_release);
  s.off_pending = !(write_register(s, dxl_x::kTorqueEnable, {&zero, 1}) &&
                    write_register(s, dxl_x::kBusWatchdog, {&zero, 1}));
  return !s.off_pending;
}

void DynamixelBus::sync_write_goals() {
  std::uint8_t ids[kMaxActuators];
  std::uint8_t data[kMaxActuators * 4];
  std::size_t n = 0;
  for (const auto& sp : servos_) {
    const Servo& s = *sp;
    if (s.stage != Stage::kOn) continue;
    const bool fresh = current_.epoch != 0 && current_.epoch >= s.on_epoch;
    std::int64_t goal =
        fresh ? s.encoding.encode(current_.positions[s.index]) : static_cast<std::int64_t>(s.hold);
    // The servo's own limits refuse a goal outside them with a Data Range
    // error that a sync write cannot report: clamp here so none is lost.
    goal = std::clamp<std::int64_t>(goal, s.min_pulse, s.max_pulse);
    ids[n] = s.id;
    dxl_x::put_i32(data + 4 * n, static_cast<std::int32_t>(goal));
    ++n;
  }
  if (n == 0) return;
  const std::size_t len =
      dxl2::encode_sync_write(dxl_x::kGoalPosition, 4, {ids, n}, {data, 4 * n}, tx_);
  if (!link_->send({tx_.data(), len}, seconds_ns(options_.response_timeout_s))) {
    lose_port(port_lost_.c_str());
  }
}

void DynamixelBus::sync_read_feedback(std::int64_t now_ns) {
  std::uint8_t ids[kMaxActuators];
  std::size_t n = 0;
  for (auto& sp : servos_) {
    sp->answered = false;
    if (sp->stage != Stage::kSetUp) ids[n++] = sp->id;
  }
  if (n == 0) return;
  const std::size_t len =
      dxl2::encode_sync_read(dxl_x::kFeedbackAddress, dxl_x::kFeedbackLength, {ids, n}, tx_);
  if (!link_->send({tx_.data(), len}, seconds_ns(options_.response_timeout_s))) {
    lose_port(port_lost_.c_str());
    return;
  }
  // Each servo answers in the order of the request, after the one before it
  // and its own return delay.
  const double reply_s =
      link_->wire_s(kStatusOverhead + dxl_x::kFeedbackLength) + options_.return_delay_us * 1e-6;
  const std::int64_t deadline =
      monotonic_ns() + seconds_ns(link_->wire_s(len) + options_.response_timeout_s +
                                  reply_s * static_cast<double>(n));
  const int got = link_->receive(
      static_cast<int>(n), deadline,
      [&](std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> p) {
        for (auto& sp : servos_) {
          Servo& s = *sp;
          if (s.id != id || s.stage == Stage::kSetUp) continue;
          if ((error & 0x7F) != 0 || p.size() != dxl_x::kFeedbackLength) return;
          s.answered = true;
          s.alert = s.alert || (error & dxl2::kErrorAlert) != 0;
          s.last_ok_ns = now_ns;
          const auto raw_load = static_cast<std::int16_t>(dxl_x::get_u16(p.data()));
          s.present = dxl_x::get_i32(p.data() + (dxl_x::kPresentPosition - dxl_x::kPresentLoad));
          ActuatorHealth& h = measured_.health[s.index];
          if (s.current_unit_a > 0.0) {
            h.current_a = raw_load * s.current_unit_a;
          } else {
            h.load = raw_load * 1e-3;
          }
          h.voltage_v =
              0.1 * dxl_x::get_u16(p.data() + (dxl_x::kPresentInputVoltage - dxl_x::kPresentLoad));
          h.temperature_c = p[dxl_x::kPresentTemperature - dxl_x::kPresentLoad];
          measured_.positions[s.index] = s.encoding.decode(s.present);
          // A servo that answers again after a silence is no longer silent.
          if (s.reason.load(std::memory_order_relaxed) == s.silent.c_str()) {
            s.reason.store(nullptr, std::memory_order_release);
          }
          return;
        }
      });
  if (got < 0) {
    lose_port(port_lost_.c_str());
    return;
  }
  for (auto& sp : servos_) {
    Servo& s = *sp;
    if (s.stage == Stage::kSetUp || s.answered) continue;
    if (now_ns - s.last_ok_ns > seconds_ns(options_.fault_after_s)) {
      // Silent too long: it may have lost power and come back with its RAM
      // (torque, watchdog, status level) at defaults, so it is set up anew.
      fail(s, s.silent.c_str());
      if (s.stage == Stage::kOn || s.wanted.load(std::memory_order_acquire)) latch_off(s);
      s.stage = Stage::kSetUp;
      s.on.store(false, std::memory_order_release);
      s.ready.store(false, std::memory_order_release);
    }
  }
}

void DynamixelBus::check_hardware_error(Servo& s) {
  std::uint8_t bits = 0;
  if (!read_register(s, dxl_x::kHardwareErrorStatus, {&bits, 1})) return;
  s.alert = false;
  measured_.health[s.index].hardware_error = bits;
  if (bits == 0) return;
  std::size_t k = 0;
  while (k < std::size(kErrorOrder) && (bits & kErrorOrder[k]) == 0) ++k;
  s.hardware_fault = true;
  fail(s, s.hardware[k].c_str());
  // The servo switches itself off only for the bits in its Shutdown item
  // (63): torque off for any of them.
  switch_torque(s, false);
  latch_off(s);
}

bool DynamixelBus::transact(Servo& s, std::span<const std::uint8_t> packet,
                            std::span<std::uint8_t> data) {
  std::uint8_t error = 0;
  const DynamixelLink::Reply r = link_->request(s.id, packet, data, options_.response_timeout_s,
                                                options_.return_delay_us * 1e-6, &error);
  if (r == DynamixelLink::Reply::kLost) {
    lose_port(port_lost_.c_str());
    return false;
  }
  if (r != DynamixelLink::Reply::kOk) return false;
  s.alert = s.alert || (error & dxl2::kErrorAlert) != 0;
  s.last_ok_ns = monotonic_ns();
  return true;
}

bool DynamixelBus::read_register(Servo& s, std::uint16_t address, std::span<std::uint8_t> data) {
  const std::size_t n =
      dxl2::encode_read(s.id, address, static_cast<std::uint16_t>(data.size()), tx_);
  return transact(s, {tx_.data(), n}, data);
}

bool DynamixelBus::write_register(Servo& s, std::uint16_t address,
                                  std::span<const std::uint8_t> data) {
  const std::size_t n = dxl2::encode_write(s.id, address, data, tx_);
  return transact(s, {tx_.data(), n}, {});
}

}  // namespace facectl
