#include "drivers/maestro/maestro_bus.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "control/clock.hpp"
#include "control/realtime/atomic_max.hpp"

namespace facectl {

namespace {

std::int64_t seconds_ns(double s) {
  return static_cast<std::int64_t>(std::llround(s * 1e9));
}

// The header of a command: 1 byte compact, 3 bytes Pololu (0xAA, device, command).
std::size_t header_bytes(maestro::Protocol p) {
  return p == maestro::Protocol::kCompact ? 1 : 3;
}

}  // namespace

struct MaestroBus::Channel {
  int channel = 0;
  std::size_t index = 0;  // actuator index in this bus
  WireEncoding encoding;
  int min_q = 0;  // the rig's hard limits, in quarter-µs
  int max_q = 0;
  // I/O thread only.
  bool on = false;
  int hold_q = 0;      // target while no command newer than the switch-on
  int position_q = 0;  // what the Maestro last said it sends (0: no pulses)
  std::uint32_t on_epoch = 0;
  // Switched off by a fault: not on again until the controller has disabled it.
  bool latched = false;
  std::uint32_t latched_disables = 0;
  // Shared with the tick.
  std::atomic<bool> wanted{false};
  std::atomic<std::uint32_t> disables{0};  // falling edges of `wanted`, from the tick
  std::atomic<bool> output{false};
};

MaestroBus::MaestroBus(std::string name, std::string device, long baud,
                       const std::vector<ActuatorModel>& actuators,
                       const std::vector<double>& initial_positions, MaestroOptions options)
    : name_(std::move(name)),
      device_(std::move(device)),
      baud_(baud),
      options_(options),
      to_{options.protocol, options.device_number},
      count_(actuators.size()) {
  const auto refuse = [&](const std::string& what) {
    throw std::invalid_argument("bus " + name_ + ": " + what);
  };
  if (count_ > kMax) refuse(std::to_string(count_) + " channels, at most 24");
  if (initial_positions.size() != count_) refuse("one initial position per actuator");
  if (baud_ <= 0) refuse("baud " + std::to_string(baud_));
  if (options_.device_number < 0 || options_.device_number > 127) refuse("device number 0..127");
  if (options_.response_timeout_s <= 0.0 || options_.cycle_period_s <= 0.0 ||
      options_.fault_after_s <= options_.response_timeout_s) {
    refuse("invalid Maestro timing");
  }
  int lo_channel = maestro::kMaxChannels, hi_channel = -1;
  for (std::size_t i = 0; i < count_; ++i) {
    const ActuatorModel& a = actuators[i];
    if (a.address < 0 || a.address >= maestro::kMaxChannels) {
      refuse("actuator " + a.name + ": channel " + std::to_string(a.address) + ", expected 0..23");
    }
    for (const auto& other : channels_) {
      if (other->channel == a.address) {
        refuse("actuators " + actuators[other->index].name + " and " + a.name + " share channel " +
               std::to_string(a.address));
      }
    }
    auto c = std::make_unique<Channel>();
    c->channel = a.address;
    c->index = i;
    c->encoding = WireEncoding(a.kind, a.encoding);
    const std::int64_t lo = 4 * c->encoding.encode(a.limits.position_min);
    const std::int64_t hi = 4 * c->encoding.encode(a.limits.position_max);
    c->min_q = static_cast<int>(std::min(lo, hi));
    c->max_q = static_cast<int>(std::max(lo, hi));
    // 0 means "no pulses": a hard limit must be a real pulse.
    if (c->min_q <= 0 || c->max_q > maestro::kMaxTarget) {
      refuse("actuator " + a.name + ": its hard limits are pulses " + std::to_string(c->min_q / 4) +
             ".." + std::to_string(c->max_q / 4) +
             " us, outside the Maestro's 1..4095 us (check encoding)");
    }
    lo_channel = std::min(lo_channel, a.address);
    hi_channel = std::max(hi_channel, a.address);
    last_feedback_.positions[i] = initial_positions[i];
    channels_.push_back(std::move(c));
  }
  if (options_.multiple_targets && count_ > 0 &&
      hi_channel - lo_channel + 1 != static_cast<int>(count_)) {
    refuse("multiple_targets sets one block of channels: channels " + std::to_string(lo_channel) +
           ".." + std::to_string(hi_channel) + " must all be actuators of the bus");
  }
  first_channel_ = lo_channel;
  port_lost_ = name_ + ": serial port " + device_ + " lost or cannot be opened";
  silent_ = name_ + ": the Maestro at " + device_ + " is not answering within " +
            std::to_string(std::lround(options_.fault_after_s * 1e3)) +
            " ms (serial mode, baud rate, protocol, device number?)";
  for (int b = 0; b < 16; ++b) {
    error_reasons_[b] =
        name_ + ": Maestro error: " + maestro::error_text(static_cast<std::uint16_t>(1u << b)) +
        " (outputs off; see docs/PROTOCOLS.md, Maestro)";
  }
  multiple_refused_ = name_ +
                      ": Maestro error: serial protocol error with multiple_targets: true (a "
                      "Micro Maestro 6 has no Set Multiple Targets; set it false)";
  measured_ = last_feedback_;
  const std::size_t h = header_bytes(options_.protocol);
  tx_.resize(count_ * (h + 3) + 2 * kMax + h + 2 + count_ * (h + 1) + h + 8);
  rx_.resize(2 * (count_ + 1));
  last_ok_ns_ = monotonic_ns();  // the silence runs from start-up
  thread_ = std::thread([this] { io_loop(); });
}

MaestroBus::~MaestroBus() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  if (port_) {
    // Pulses off on the way out, whatever the controller did.
    for (auto& c : channels_) {
      c->on = false;
      c->latched = true;
    }
    send_targets();
  }
}

// Tick side: mailboxes and atomics only.

void MaestroBus::read(const TickTime& /*time*/, std::span<double> positions) {
  feedback_.consume(last_feedback_);
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    positions[i] = last_feedback_.positions[i];
  }
}

void MaestroBus::read_health(std::span<ActuatorHealth> health) {
  feedback_.consume(last_feedback_);
  for (std::size_t i = 0; i < count_ && i < health.size(); ++i) {
    health[i] = last_feedback_.health[i];
  }
}

void MaestroBus::write(const TickTime& /*time*/, std::span<const double> positions) {
  if (!enabled_.load(std::memory_order_relaxed)) return;
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    staging_.positions[i] = positions[i];
  }
  staging_.epoch = epoch_.load(std::memory_order_relaxed);
  commands_.publish(staging_);
}

void MaestroBus::set_enabled(bool enabled) {
  if (enabled && !enabled_.load(std::memory_order_relaxed)) {
    epoch_.fetch_add(1, std::memory_order_release);
  }
  for (auto& c : channels_) {
    if (!enabled && c->wanted.load(std::memory_order_relaxed)) {
      c->disables.fetch_add(1, std::memory_order_release);
    }
    c->wanted.store(enabled, std::memory_order_release);
  }
  enabled_.store(enabled, std::memory_order_release);
}

void MaestroBus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  bool any = false;
  bool rising = false;
  for (auto& c : channels_) {
    const bool on = c->index < enabled.size() && enabled[c->index] != 0;
    any = any || on;
    rising = rising || (on && !c->wanted.load(std::memory_order_relaxed));
  }
  // A new epoch before any channel is wanted: a channel switched on never
  // takes a command written before.
  if (rising) epoch_.fetch_add(1, std::memory_order_release);
  for (auto& c : channels_) {
    const bool on = c->index < enabled.size() && enabled[c->index] != 0;
    if (!on && c->wanted.load(std::memory_order_relaxed)) {
      c->disables.fetch_add(1, std::memory_order_release);
    }
    c->wanted.store(on, std::memory_order_release);
  }
  enabled_.store(any, std::memory_order_release);
}

BusStatus MaestroBus::status() const {
  BusStatus st;
  const char* r = port_reason_.load(std::memory_order_acquire);
  if (r == nullptr) r = reason_.load(std::memory_order_acquire);
  if (r != nullptr) {
    st.fault = true;
    st.reason = r;
  }
  st.frames_sent = stats_.cycles.load(std::memory_order_relaxed);
  st.errors = stats_.timeouts.load(std::memory_order_relaxed) +
              stats_.short_replies.load(std::memory_order_relaxed) +
              stats_.error_reports.load(std::memory_order_relaxed);
  return st;
}

bool MaestroBus::output_on(std::size_t actuator) const {
  return actuator < channels_.size() && channels_[actuator]->output.load(std::memory_order_acquire);
}

MaestroStats MaestroBus::stats() const {
  MaestroStats s;
  s.cycles = stats_.cycles.load(std::memory_order_relaxed);
  s.replies = stats_.replies.load(std::memory_order_relaxed);
  s.timeouts = stats_.timeouts.load(std::memory_order_relaxed);
  s.short_replies = stats_.short_replies.load(std::memory_order_relaxed);
  s.error_reports = stats_.error_reports.load(std::memory_order_relaxed);
  s.reopens = stats_.reopens.load(std::memory_order_relaxed);
  s.max_cycle_ns = stats_.max_cycle_ns.load(std::memory_order_relaxed);
  return s;
}

// I/O thread.

void MaestroBus::io_loop() {
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  const std::int64_t period = seconds_ns(options_.cycle_period_s);
  while (!stop_.load(std::memory_order_acquire)) {
    const std::int64_t start = monotonic_ns();
    if (open_port(start)) run_cycle(start);
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

bool MaestroBus::open_port(std::int64_t now_ns) {
  if (port_) return true;
  if (now_ns - last_open_attempt_ns_ < seconds_ns(options_.reconnect_interval_s)) return false;
  const bool reopening = last_open_attempt_ns_ > 0;
  last_open_attempt_ns_ = now_ns;
  try {
    port_ = std::make_unique<SerialPort>(device_, baud_);
  } catch (const std::runtime_error&) {
    port_reason_.store(port_lost_.c_str(), std::memory_order_release);
    return false;
  }
  if (reopening) stats_.reopens.fetch_add(1, std::memory_order_relaxed);
  port_reason_.store(nullptr, std::memory_order_release);
  last_ok_ns_ = now_ns;  // a new port: the silence runs from here
  return true;
}

void MaestroBus::lose_port() {
  port_.reset();
  port_reason_.store(port_lost_.c_str(), std::memory_order_release);
  ready_.store(false, std::memory_order_release);
  latch_all();
}

void MaestroBus::latch_all() {
  for (auto& c : channels_) {
    // Wanted but not yet on counts too: it must not come on by itself.
    if ((c->on || c->wanted.load(std::memory_order_acquire)) && !c->latched) {
      c->latched = true;
      c->latched_disables = c->disables.load(std::memory_order_acquire);
    }
    c->on = false;
    c->output.store(false, std::memory_order_release);
  }
}

void MaestroBus::run_cycle(std::int64_t now_ns) {
  Command fresh;
  if (commands_.consume(fresh)) current_ = fresh;
  update_outputs();
  if (!send_targets()) {
    lose_port();
    return;
  }
  read_back(now_ns);
}

// Which channels send pulses this cycle.
void MaestroBus::update_outputs() {
  bool all_released = true;
  for (auto& cp : channels_) {
    Channel& c = *cp;
    const bool wanted = c.wanted.load(std::memory_order_acquire);
    if (c.latched &&
        (!wanted || c.disables.load(std::memory_order_acquire) != c.latched_disables)) {
      c.latched = false;  // the controller has disabled it since
    }
    all_released = all_released && !c.latched;
    const bool faulted = error_bits_ != 0 || reason_.load(std::memory_order_relaxed) != nullptr;
    const bool want = wanted && !c.latched && !faulted && ready_.load(std::memory_order_relaxed);
    if (want && !c.on) {
      // Bumpless: the pulse it was last sending, else the last position
      // reported, until the tick writes after this enable.
      c.hold_q = c.position_q != 0
                     ? c.position_q
                     : static_cast<int>(4 * c.encoding.encode(measured_.positions[c.index]));
      c.hold_q = std::clamp(c.hold_q, c.min_q, c.max_q);
      c.on_epoch = epoch_.load(std::memory_order_acquire);
    }
    c.on = want;
    c.output.store(want, std::memory_order_release);
  }
  // Error bits stay a fault until every channel has been disabled since.
  if (all_released) error_bits_ = 0;
}

bool MaestroBus::send_targets() {
  std::uint16_t q[kMax] = {};
  for (const auto& cp : channels_) {
    const Channel& c = *cp;
    int target = 0;  // no pulses
    if (c.on) {
      const bool fresh = current_.epoch != 0 && current_.epoch >= c.on_epoch;
      const std::int64_t want =
          fresh ? 4 * c.encoding.encode(current_.positions[c.index]) : c.hold_q;
      target = static_cast<int>(std::clamp<std::int64_t>(want, c.min_q, c.max_q));
    }
    q[c.index] = static_cast<std::uint16_t>(target);
  }
  std::size_t n = 0;
  std::span<std::uint8_t> out(tx_);
  if (options_.multiple_targets && count_ > 0) {
    std::uint16_t block[kMax] = {};
    for (const auto& c : channels_) block[c->channel - first_channel_] = q[c->index];
    n = maestro::encode_set_multiple_targets(to_, first_channel_, {block, count_}, out);
  } else {
    for (const auto& c : channels_) {
      n += maestro::encode_set_target(to_, c->channel, q[c->index], out.subspan(n));
    }
  }
  if (n == 0) return true;
  const double wire_s = serial_byte_s(baud_) * static_cast<double>(n);
  return port_->write_all({tx_.data(), n}, seconds_ns(wire_s + options_.response_timeout_s));
}

void MaestroBus::read_back(std::int64_t now_ns) {
  // Every Get Position and Get Errors in one write; the replies come in order.
  std::size_t n = 0;
  std::span<std::uint8_t> out(tx_);
  for (const auto& c : channels_)
    n += maestro::encode_get_position(to_, c->channel, out.subspan(n));
  n += maestro::encode_get_errors(to_, out.subspan(n));
  port_->discard_input();  // a late reply is not the answer to these
  const double wire_s = serial_byte_s(baud_) * static_cast<double>(n + rx_.size());
  if (!port_->write_all({tx_.data(), n}, seconds_ns(wire_s + options_.response_timeout_s))) {
    lose_port();
    return;
  }
  const std::int64_t deadline = monotonic_ns() + seconds_ns(wire_s + options_.response_timeout_s);
  std::size_t got = 0;
  while (got < rx_.size()) {
    const std::int64_t left = deadline - monotonic_ns();
    if (left <= 0) break;
    const long r = port_->read_some({rx_.data() + got, rx_.size() - got}, left);
    if (r < 0) {
      lose_port();
      return;
    }
    got += static_cast<std::size_t>(r);
  }
  if (got < rx_.size()) {
    (got == 0 ? stats_.timeouts : stats_.short_replies).fetch_add(1, std::memory_order_relaxed);
    if (now_ns - last_ok_ns_ > seconds_ns(options_.fault_after_s)) {
      // Silent too long: the Maestro may have reset (its outputs at their
      // power-up settings); everything off until the controller disables.
      if (reason_.load(std::memory_order_relaxed) == nullptr) {
        reason_.store(silent_.c_str(), std::memory_order_release);
      }
      ready_.store(false, std::memory_order_release);
      latch_all();
    }
    return;
  }
  // The replies carry no framing: a late byte of an earlier cycle shifts them
  // all. Error bits the Maestro does not have (above bit 8) show such a shift.
  if ((maestro::reply_u16(&rx_[2 * count_]) & ~0x01FFu) != 0) {
    stats_.short_replies.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  stats_.replies.fetch_add(1, std::memory_order_relaxed);
  last_ok_ns_ = now_ns;
  if (reason_.load(std::memory_order_relaxed) == silent_.c_str()) {
    reason_.store(nullptr, std::memory_order_release);
  }
  for (const auto& cp : channels_) {
    Channel& c = *cp;
    c.position_q = maestro::reply_u16(&rx_[2 * c.index]);
    // 0: no pulses, nothing to report; the last position stands.
    if (c.position_q != 0) {
      measured_.positions[c.index] = c.encoding.decode(std::llround(c.position_q / 4.0));
    }
  }
  take_errors(maestro::reply_u16(&rx_[2 * count_]));
}

void MaestroBus::take_errors(std::uint16_t bits) {
  const auto report = [&] {
    for (std::size_t i = 0; i < count_; ++i) measured_.health[i].hardware_error = error_bits_;
  };
  if (bits == 0) {
    report();
    if (error_bits_ == 0) {
      const char* r = reason_.load(std::memory_order_relaxed);
      if (r != nullptr && r != silent_.c_str()) reason_.store(nullptr, std::memory_order_release);
      ready_.store(true, std::memory_order_release);
    }
    return;
  }
  // Reading the register cleared it: the bits are kept here, and the outputs
  // go off (the Maestro has already sent its servos to their home settings).
  stats_.error_reports.fetch_add(1, std::memory_order_relaxed);
  error_bits_ |= bits;
  report();
  const std::uint16_t worst = maestro::worst_error(bits);
  int b = 0;
  while (b < 15 && (worst >> b) != 1) ++b;
  const bool refused_block = options_.multiple_targets && (bits & maestro::kErrSerialProtocol) != 0;
  reason_.store(refused_block ? multiple_refused_.c_str() : error_reasons_[b].c_str(),
                std::memory_order_release);
  latch_all();
}

}  // namespace facectl
