#include "drivers/feetech/feetech_bus.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "control/clock.hpp"
#include "control/realtime/atomic_max.hpp"
#include "drivers/protocol/feetech_packet.hpp"
#include "drivers/protocol/feetech_table.hpp"

namespace facectl {

namespace {

std::int64_t seconds_ns(double s) {
  return static_cast<std::int64_t>(std::llround(s * 1e9));
}

// The error bits, worst first: the one a FAULT names.
constexpr std::uint8_t kErrorOrder[] = {ft::kErrOverCurrent, ft::kErrOverheat, ft::kErrOverload,
                                        ft::kErrAngle, ft::kErrVoltage};
constexpr std::size_t kErrorReasons = std::size(kErrorOrder) + 1;  // + "other bits"

}  // namespace

struct FeetechBus::Servo {
  std::uint8_t id = 0;
  std::size_t index = 0;
  WireEncoding encoding;
  std::int32_t min_step = 0;  // the rig's hard limits, in the servo's steps
  std::int32_t max_step = 0;
  // I/O thread only.
  Stage stage = Stage::kSetUp;
  std::int64_t last_ok_ns = 0;
  std::int32_t present = 0;
  std::int32_t hold = 0;  // goal while no command newer than the torque-on
  std::uint32_t on_epoch = 0;
  bool answered = false;
  std::uint8_t error = 0;  // of this cycle's feedback, acted on after the read
  bool hardware_fault = false;
  bool off_pending = false;
  bool latched = false;  // switched off by a fault until the controller disables it
  std::uint32_t latched_disables = 0;
  std::string silent, refused, hardware[kErrorReasons];  // static reasons
  // Shared with the tick.
  std::atomic<const char*> reason{nullptr};
  std::atomic<bool> wanted{false};
  std::atomic<std::uint32_t> disables{0};
  std::atomic<bool> on{false};
  std::atomic<bool> ready{false};
};

FeetechBus::FeetechBus(std::string name, std::string device, long baud,
                       const std::vector<ActuatorModel>& actuators,
                       const std::vector<double>& initial_positions, FeetechOptions options)
    : name_(std::move(name)),
      device_(std::move(device)),
      baud_(baud),
      options_(options),
      series_(options.series),
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
      options_.return_delay_us > 508) {
    refuse("invalid Feetech timing");
  }
  const int top = ft::steps_per_turn(series_) - 1;
  for (std::size_t i = 0; i < count_; ++i) {
    const ActuatorModel& a = actuators[i];
    if (a.address < 0 || a.address > scs::kMaxId) {
      refuse("actuator " + a.name + ": servo ID " + std::to_string(a.address) + ", expected 0.." +
             std::to_string(scs::kMaxId));
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
    s->min_step = static_cast<std::int32_t>(std::min(lo, hi));
    s->max_step = static_cast<std::int32_t>(std::max(lo, hi));
    if (s->min_step < 0 || s->max_step > top) {
      refuse("actuator " + a.name + ": its hard limits are steps " + std::to_string(s->min_step) +
             ".." + std::to_string(s->max_step) + ", outside the 0.." + std::to_string(top) +
             " of this series (check encoding and series)");
    }
    const std::string who = name_ + " servo " + std::to_string(a.address) + " (" + a.name + ")";
    s->silent = who + ": not answering within " +
                std::to_string(std::lround(options_.fault_after_s * 1e3)) + " ms";
    s->refused = who + ": refused its set-up (a write was not confirmed)";
    for (std::size_t k = 0; k < kErrorReasons; ++k) {
      const std::string bits =
          k < std::size(kErrorOrder) ? ft::error_text(kErrorOrder[k]) : "other bits";
      s->hardware[k] = who + ": error status: " + bits + " (torque off until it clears and the " +
                       "controller enables again)";
    }
    last_feedback_.positions[i] = initial_positions[i];
    servos_.push_back(std::move(s));
  }
  port_lost_ = name_ + ": serial port " + device_ + " lost or cannot be opened";
  measured_ = last_feedback_;
  tx_.resize(scs::kOverhead + scs::kMaxParams);
  const std::int64_t now = monotonic_ns();
  for (auto& s : servos_) s->last_ok_ns = now;
  thread_ = std::thread([this] { io_loop(); });
}

FeetechBus::~FeetechBus() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  // Torque off on the way out. Without it the servos would hold their last
  // goal for ever.
  std::uint8_t ids[kMaxActuators];
  for (std::size_t i = 0; i < count_; ++i) ids[i] = servos_[i]->id;
  broadcast_torque_off({ids, count_});
}

// Torque off with one Sync Write, which no servo answers: it also reaches a
// servo whose replies are lost (a broken return line, an ID clash), which a
// confirmed write would take for silent and leave holding its goal.
void FeetechBus::broadcast_torque_off(std::span<const std::uint8_t> ids) {
  if (!link_ || ids.empty()) return;
  static constexpr std::uint8_t kZeros[kMaxActuators] = {};
  const std::size_t n =
      scs::encode_sync_write(ft::kTorqueEnable, 1, ids, {kZeros, ids.size()}, tx_);
  if (n > 0 && !link_->send({tx_.data(), n}, seconds_ns(options_.response_timeout_s))) {
    lose_port(port_lost_.c_str());
  }
}

// Tick side: mailboxes and atomics only.

void FeetechBus::read(const TickTime& /*time*/, std::span<double> positions) {
  feedback_.consume(last_feedback_);
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    positions[i] = last_feedback_.positions[i];
  }
}

void FeetechBus::read_health(std::span<ActuatorHealth> health) {
  feedback_.consume(last_feedback_);
  for (std::size_t i = 0; i < count_ && i < health.size(); ++i) {
    health[i] = last_feedback_.health[i];
  }
}

void FeetechBus::write(const TickTime& /*time*/, std::span<const double> positions) {
  if (!enabled_.load(std::memory_order_relaxed)) return;
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    staging_.positions[i] = positions[i];
  }
  staging_.epoch = epoch_.load(std::memory_order_relaxed);
  commands_.publish(staging_);
}

void FeetechBus::set_enabled(bool enabled) {
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

void FeetechBus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  bool any = false;
  bool rising = false;
  for (auto& s : servos_) {
    const bool on = s->index < enabled.size() && enabled[s->index] != 0;
    any = any || on;
    rising = rising || (on && !s->wanted.load(std::memory_order_relaxed));
  }
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

BusStatus FeetechBus::status() const {
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
              stats_.bad_checksum.load(std::memory_order_relaxed) +
              stats_.bad_packets.load(std::memory_order_relaxed);
  return st;
}

bool FeetechBus::ready() const {
  return std::all_of(servos_.begin(), servos_.end(),
                     [](const auto& s) { return s->ready.load(std::memory_order_acquire); });
}

bool FeetechBus::torque_on(std::size_t actuator) const {
  return actuator < servos_.size() && servos_[actuator]->on.load(std::memory_order_acquire);
}

FeetechStats FeetechBus::stats() const {
  FeetechStats s;
  s.cycles = stats_.cycles.load(std::memory_order_relaxed);
  s.status_packets = stats_.status_packets.load(std::memory_order_relaxed);
  s.timeouts = stats_.timeouts.load(std::memory_order_relaxed);
  s.bad_checksum = stats_.bad_checksum.load(std::memory_order_relaxed);
  s.bad_packets = stats_.bad_packets.load(std::memory_order_relaxed);
  s.reopens = stats_.reopens.load(std::memory_order_relaxed);
  s.max_cycle_ns = stats_.max_cycle_ns.load(std::memory_order_relaxed);
  return s;
}

// I/O thread.

void FeetechBus::io_loop() {
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

bool FeetechBus::open_port(std::int64_t now_ns) {
  if (link_) return true;
  if (now_ns - last_open_attempt_ns_ < seconds_ns(options_.reconnect_interval_s)) return false;
  const bool reopening = last_open_attempt_ns_ > 0;
  last_open_attempt_ns_ = now_ns;
  try {
    link_ = std::make_unique<FeetechLink>(device_, baud_);
  } catch (const std::runtime_error&) {
    port_reason_.store(port_lost_.c_str(), std::memory_order_release);
    return false;
  }
  if (reopening) stats_.reopens.fetch_add(1, std::memory_order_relaxed);
  port_reason_.store(nullptr, std::memory_order_release);
  for (auto& s : servos_) s->stage = Stage::kSetUp;
  return true;
}

void FeetechBus::lose_port(const char* reason) {
  if (!link_) return;  // already lost, by an earlier step of this cycle
  publish_counters();
  const FeetechLink::Counters& c = link_->counters();
  counted_.status_packets += c.status_packets;
  counted_.timeouts += c.timeouts;
  counted_.bad_checksum += c.bad_checksum;
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

void FeetechBus::publish_counters() {
  if (!link_) return;
  const FeetechLink::Counters& c = link_->counters();
  stats_.status_packets.store(counted_.status_packets + c.status_packets,
                              std::memory_order_relaxed);
  stats_.timeouts.store(counted_.timeouts + c.timeouts, std::memory_order_relaxed);
  stats_.bad_checksum.store(counted_.bad_checksum + c.bad_checksum, std::memory_order_relaxed);
  stats_.bad_packets.store(counted_.bad_packets + c.bad_packets, std::memory_order_relaxed);
}

void FeetechBus::fail(Servo& s, const char* reason) {
  s.reason.store(reason, std::memory_order_release);
}

void FeetechBus::latch_off(Servo& s) {
  if (!s.latched) s.latched_disables = s.disables.load(std::memory_order_acquire);
  s.latched = true;
}

void FeetechBus::run_cycle(std::int64_t now_ns) {
  Command fresh;
  if (commands_.consume(fresh)) current_ = fresh;
  // A servo not (or no longer) set up, or whose torque-off was not
  // confirmed, may still hold torque: it is told to let go every cycle.
  std::uint8_t off[kMaxActuators];
  std::size_t n_off = 0;
  for (const auto& sp : servos_) {
    if (sp->stage == Stage::kSetUp || sp->off_pending) off[n_off++] = sp->id;
  }
  broadcast_torque_off({off, n_off});
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
  read_feedback(now_ns);
}

bool FeetechBus::set_up(Servo& s) {
  std::uint8_t b[8];
  // PING answers at every Response Level; then level 1, so that every write
  // is confirmed (level 0 answers only PING and READ).
  const std::size_t n = scs::encode_instruction(s.id, scs::kPing, {}, tx_);
  if (!transact(s, {tx_.data(), n}, {})) return false;
  if (!read_register(s, ft::kResponseLevel, {b, 1})) return false;
  if (b[0] != 1) {
    const std::uint8_t level = 1;
    write_register(s, ft::kResponseLevel, {&level, 1});  // unanswered at level 0
    if (!read_register(s, ft::kResponseLevel, {b, 1}) || b[0] != 1) return false;
  }
  const std::uint8_t zero = 0;
  bool ok = write_register(s, ft::kTorqueEnable, {&zero, 1});  // before any EEPROM write
  // Return Delay (7), Response Level (8), Min and Max Angle Limit (9..12).
  ok = ok && read_register(s, ft::kReturnDelay, {b, 6});
  if (!ok) return false;
  const auto delay = static_cast<std::uint8_t>(options_.return_delay_us / 2);
  if (b[0] != delay) ok = write_eeprom(s, ft::kReturnDelay, {&delay, 1});
  if (ok && options_.write_position_limits) {
    std::uint8_t want[4];
    ft::put_u16(series_, want, static_cast<std::uint16_t>(s.min_step));
    ft::put_u16(series_, want + 2, static_cast<std::uint16_t>(s.max_step));
    if (std::memcmp(b + 2, want, 4) != 0) ok = write_eeprom(s, ft::kMinAngleLimit, want);
  }
  if (!ok) {
    if (s.reason.load(std::memory_order_relaxed) == nullptr) fail(s, s.refused.c_str());
    return false;
  }
  std::uint8_t error = 0;
  const std::size_t r = scs::encode_read(s.id, ft::kPresentPosition, 2, tx_);
  if (!link_) return false;
  const FeetechLink::Reply reply =
      link_->request(s.id, {tx_.data(), r}, {b, 2}, options_.response_timeout_s,
                     options_.return_delay_us * 1e-6, &error);
  if (reply == FeetechLink::Reply::kLost) lose_port(port_lost_.c_str());
  if (reply != FeetechLink::Reply::kOk) return false;
  s.last_ok_ns = monotonic_ns();
  measured_.health[s.index].hardware_error = error;
  if (error != 0) {
    check_error(s, error);
    return false;
  }
  s.present = ft::sign_magnitude(ft::get_u16(series_, b), 15);
  measured_.positions[s.index] = s.encoding.decode(s.present);
  s.hardware_fault = false;
  s.reason.store(nullptr, std::memory_order_release);
  return true;
}

// EEPROM items are write-protected by Lock: open it, write, close it again
// (the SDK's unLockEprom / LockEprom).
bool FeetechBus::write_eeprom(Servo& s, std::uint8_t address, std::span<const std::uint8_t> data) {
  const std::uint8_t open = 0;
  const std::uint8_t closed = 1;
  const std::uint8_t lock = ft::lock_address(series_);
  const bool ok = write_register(s, lock, {&open, 1}) && write_register(s, address, data);
  return write_register(s, lock, {&closed, 1}) && ok;
}

bool FeetechBus::switch_torque(Servo& s, bool on) {
  const std::uint8_t zero = 0;
  if (on) {
    // Bumpless: the goal is where the servo is before the torque comes on.
    std::uint8_t b[2];
    s.hold = std::clamp(s.present, s.min_step, s.max_step);
    s.on_epoch = epoch_.load(std::memory_order_acquire);
    ft::put_u16(series_, b, static_cast<std::uint16_t>(s.hold));
    const std::uint8_t one = 1;
    if (!write_register(s, ft::kGoalPosition, {b, 2})) return false;
    s.stage = Stage::kOn;
    s.on.store(true, std::memory_order_release);
    if (write_register(s, ft::kTorqueEnable, {&one, 1})) return true;
    switch_torque(s, false);
    return false;
  }
  s.stage = s.stage == Stage::kSetUp ? Stage::kSetUp : Stage::kReady;
  s.on.store(false, std::memory_order_release);
  s.off_pending = !write_register(s, ft::kTorqueEnable, {&zero, 1});
  return !s.off_pending;
}

void FeetechBus::sync_write_goals() {
  std::uint8_t ids[kMaxActuators];
  std::uint8_t data[kMaxActuators * 2];
  std::size_t n = 0;
  for (const auto& sp : servos_) {
    const Servo& s = *sp;
    if (s.stage != Stage::kOn) continue;
    const bool fresh = current_.epoch != 0 && current_.epoch >= s.on_epoch;
    std::int64_t goal =
        fresh ? s.encoding.encode(current_.positions[s.index]) : static_cast<std::int64_t>(s.hold);
    goal = std::clamp<std::int64_t>(goal, s.min_step, s.max_step);
    ids[n] = s.id;
    ft::put_u16(series_, data + 2 * n, static_cast<std::uint16_t>(goal));
    ++n;
  }
  if (n == 0) return;
  const std::size_t len =
      scs::encode_sync_write(ft::kGoalPosition, 2, {ids, n}, {data, 2 * n}, tx_);
  if (!link_->send({tx_.data(), len}, seconds_ns(options_.response_timeout_s))) {
    lose_port(port_lost_.c_str());
  }
}

void FeetechBus::take_feedback(Servo& s, std::uint8_t error, std::span<const std::uint8_t> p,
                               std::int64_t now_ns) {
  if (p.size() != ft::kFeedbackLength) return;
  s.answered = true;
  s.last_ok_ns = now_ns;
  s.present = ft::sign_magnitude(ft::get_u16(series_, p.data()), 15);
  ActuatorHealth& h = measured_.health[s.index];
  // Present Load: sign bit 10, 0.1 % of the maximum torque a unit.
  h.load = ft::sign_magnitude(ft::get_u16(series_, p.data() + 4), 10) * 1e-3;
  h.voltage_v = 0.1 * p[ft::kPresentVoltage - ft::kFeedbackAddress];
  h.temperature_c = p[ft::kPresentTemperature - ft::kFeedbackAddress];
  h.hardware_error = error;
  s.error = error;
  measured_.positions[s.index] = s.encoding.decode(s.present);
  if (s.reason.load(std::memory_order_relaxed) == s.silent.c_str()) {
    s.reason.store(nullptr, std::memory_order_release);
  }
}

void FeetechBus::read_feedback(std::int64_t now_ns) {
  std::uint8_t ids[kMaxActuators];
  std::size_t n = 0;
  for (auto& sp : servos_) {
    sp->answered = false;
    if (sp->stage != Stage::kSetUp) ids[n++] = sp->id;
  }
  if (n == 0) return;
  if (series_ == ft::Series::kSts) {
    const std::size_t len =
        scs::encode_sync_read(ft::kFeedbackAddress, ft::kFeedbackLength, {ids, n}, tx_);
    if (!link_->send({tx_.data(), len}, seconds_ns(options_.response_timeout_s))) {
      lose_port(port_lost_.c_str());
      return;
    }
    const double reply_s =
        link_->wire_s(scs::kOverhead + ft::kFeedbackLength) + options_.return_delay_us * 1e-6;
    const std::int64_t deadline =
        monotonic_ns() + seconds_ns(link_->wire_s(len) + options_.response_timeout_s +
                                    reply_s * static_cast<double>(n));
    const int got =
        link_->receive(static_cast<int>(n), deadline,
                       [&](std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> p) {
                         for (auto& sp : servos_) {
                           if (sp->id == id && sp->stage != Stage::kSetUp)
                             take_feedback(*sp, error, p, now_ns);
                         }
                       });
    if (got < 0) {
      lose_port(port_lost_.c_str());
      return;
    }
  } else {
    // SCS has no Sync Read: one Read per servo.
    std::uint8_t p[ft::kFeedbackLength];
    for (auto& sp : servos_) {
      Servo& s = *sp;
      if (s.stage == Stage::kSetUp) continue;
      std::uint8_t error = 0;
      const std::size_t len =
          scs::encode_read(s.id, ft::kFeedbackAddress, ft::kFeedbackLength, tx_);
      const FeetechLink::Reply r =
          link_->request(s.id, {tx_.data(), len}, p, options_.response_timeout_s,
                         options_.return_delay_us * 1e-6, &error);
      if (r == FeetechLink::Reply::kLost) {
        lose_port(port_lost_.c_str());
        return;
      }
      if (r == FeetechLink::Reply::kOk) take_feedback(s, error, p, now_ns);
    }
  }
  for (auto& sp : servos_) {
    Servo& s = *sp;
    if (link_ && s.answered) check_error(s, s.error);
    if (s.stage == Stage::kSetUp || s.answered) continue;
    if (now_ns - s.last_ok_ns > seconds_ns(options_.fault_after_s)) {
      // Silent too long: it may have lost power and come back with its RAM
      // (torque, response level) at defaults, so it is set up anew.
      fail(s, s.silent.c_str());
      if (s.stage == Stage::kOn || s.wanted.load(std::memory_order_acquire)) latch_off(s);
      s.stage = Stage::kSetUp;
      s.on.store(false, std::memory_order_release);
      s.ready.store(false, std::memory_order_release);
    }
  }
}

// The error byte of every status packet carries the servo's protection
// flags, which clear by themselves when the condition passes. Torque goes
// off on any, and stays off until the flags are clear and the controller
// has disabled and enabled again.
void FeetechBus::check_error(Servo& s, std::uint8_t error) {
  if (error == 0) {
    if (s.hardware_fault) {
      s.hardware_fault = false;
      s.reason.store(nullptr, std::memory_order_release);
    }
    return;
  }
  std::size_t k = 0;
  while (k < std::size(kErrorOrder) && (error & kErrorOrder[k]) == 0) ++k;
  fail(s, s.hardware[k].c_str());
  if (s.hardware_fault) return;
  s.hardware_fault = true;
  // Latched even if it was not on yet: it must not come on by itself once
  // the flags clear.
  if (s.stage == Stage::kOn || s.wanted.load(std::memory_order_acquire)) latch_off(s);
  if (s.stage == Stage::kOn) switch_torque(s, false);
}

bool FeetechBus::transact(Servo& s, std::span<const std::uint8_t> packet,
                          std::span<std::uint8_t> data) {
  if (!link_) return false;  // lost by an earlier step of this cycle
  std::uint8_t error = 0;
  const FeetechLink::Reply r = link_->request(s.id, packet, data, options_.response_timeout_s,
                                              options_.return_delay_us * 1e-6, &error);
  if (r == FeetechLink::Reply::kLost) {
    lose_port(port_lost_.c_str());
    return false;
  }
  if (r != FeetechLink::Reply::kOk) return false;
  s.last_ok_ns = monotonic_ns();
  return true;
}

bool FeetechBus::read_register(Servo& s, std::uint8_t address, std::span<std::uint8_t> data) {
  const std::size_t n =
      scs::encode_read(s.id, address, static_cast<std::uint8_t>(data.size()), tx_);
  return transact(s, {tx_.data(), n}, data);
}

bool FeetechBus::write_register(Servo& s, std::uint8_t address,
                                std::span<const std::uint8_t> data) {
  const std::size_t n = scs::encode_write(s.id, address, data, tx_);
  return transact(s, {tx_.data(), n}, {});
}

}  // namespace facectl
