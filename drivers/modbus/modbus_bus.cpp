#include "drivers/modbus/modbus_bus.hpp"

#include <modbus/modbus.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "control/clock.hpp"
#include "control/realtime/atomic_max.hpp"
#include "drivers/modbus/modbus_timeouts.hpp"

namespace facectl {

namespace {

// Baud rates libmodbus 3.1.6 maps to termios constants. Any other value makes
// it print a warning and silently use 9600 baud, so we refuse it up front.
bool known_baud(long baud) {
  for (long b : {1200L,    2400L,    4800L,    9600L,    19200L,   38400L,   57600L,
                 115200L,  230400L,  460800L,  500000L,  576000L,  921600L,  1000000L,
                 1152000L, 1500000L, 2000000L, 2500000L, 3000000L, 3500000L, 4000000L}) {
    if (b == baud) return true;
  }
  return false;
}

}  // namespace

ModbusEndpoint ModbusEndpoint::parse(const std::string& type, const std::string& endpoint,
                                     long baud) {
  ModbusEndpoint e;
  if (type == "modbus_tcp") {
    e.tcp = true;
    const auto colon = endpoint.rfind(':');
    e.host = endpoint.substr(0, colon);
    if (colon != std::string::npos) {
      const std::string port = endpoint.substr(colon + 1);
      char* end = nullptr;
      const long p = std::strtol(port.c_str(), &end, 10);
      if (port.empty() || *end != '\0' || p < 1 || p > 65535) {
        throw std::invalid_argument("modbus_tcp endpoint '" + endpoint +
                                    "': expected host[:port] with a port in 1..65535, found '" +
                                    port + "'");
      }
      e.port = static_cast<int>(p);
    }
    if (e.host.empty()) {
      throw std::invalid_argument("modbus_tcp endpoint '" + endpoint + "': empty host");
    }
  } else if (type == "modbus_rtu") {
    e.tcp = false;
    e.device = endpoint;
    if (!known_baud(baud)) {
      throw std::invalid_argument("modbus_rtu " + endpoint + ": baud " + std::to_string(baud) +
                                  " is not a standard rate (libmodbus would fall back to 9600)");
    }
    e.baud = static_cast<int>(baud);
  } else {
    throw std::invalid_argument("not a Modbus bus type: '" + type + "'");
  }
  return e;
}

ModbusBus::ModbusBus(std::string name, ModbusEndpoint endpoint,
                     const std::vector<ActuatorModel>& actuators,
                     const std::vector<double>& initial_positions, ModbusTiming timing,
                     modbus_map::Addresses registers)
    : name_(std::move(name)),
      endpoint_(std::move(endpoint)),
      timing_(timing),
      registers_(registers),
      count_(actuators.size()) {
  if (count_ > kMaxActuators) {
    throw std::invalid_argument("bus " + name_ + ": " + std::to_string(count_) +
                                " actuators, at most " + std::to_string(kMaxActuators));
  }
  if (initial_positions.size() != count_) {
    throw std::invalid_argument("bus " + name_ + ": one initial position per actuator");
  }
  if (timing_.response_timeout_s <= 0.0 || timing_.max_retries < 0 ||
      timing_.board_watchdog_ms < 1 || timing_.board_watchdog_ms > 65535) {
    throw std::invalid_argument("bus " + name_ + ": invalid Modbus timing");
  }
  for (std::size_t i = 0; i < count_; ++i) {
    const ActuatorModel& a = actuators[i];
    const modbus_map::Placement p = modbus_map::place(a.address);  // throws naming the address
    const auto unit =
        a.kind == ActuatorKind::kRotary ? modbus_map::Unit::kRotary : modbus_map::Unit::kLinear;
    try {
      encodings_.push_back(modbus_map::channel_encoding(unit, a.encoding));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name + ": " + e.what());
    }
    std::size_t b = 0;
    while (b < boards_.size() && boards_[b]->unit != p.unit) ++b;
    if (b == boards_.size()) {
      boards_.push_back(std::make_unique<Board>());
      boards_[b]->unit = p.unit;
      boards_[b]->actuator.assign(modbus_map::kChannelsPerBoard, SIZE_MAX);
    }
    Board& board = *boards_[b];
    const auto ch = static_cast<std::size_t>(p.channel);
    if (board.actuator[ch] != SIZE_MAX) {
      throw std::invalid_argument("bus " + name_ + ": actuators " +
                                  actuators[board.actuator[ch]].name + " and " + a.name +
                                  " share address " + std::to_string(a.address));
    }
    board.actuator[ch] = i;
    board.channels = std::max(board.channels, p.channel + 1);
    board_of_.push_back(b);
    last_feedback_.positions[i] = initial_positions[i];
  }
  for (auto& bp : boards_) {
    Board& b = *bp;
    const std::string who = name_ + " board " + std::to_string(b.unit);
    b.silent = who + ": not answering within " +
               std::to_string(std::lround(timing_.response_timeout_s * 1000)) + " ms";
    b.exception = who + ": answers with exception responses";
    b.bad_reply = who + ": corrupt replies";
    b.link = who + ": connection lost";
    b.fault = who + ": reports a fault";
    b.watchdog = who + ": watchdog tripped";
  }
  measured_ = last_feedback_;
  const std::int64_t now = monotonic_ns();
  for (auto& b : boards_) b->last_ok_ns = now;  // the timeout runs from start-up
  thread_ = std::thread([this] { io_loop(); });
}

ModbusBus::~ModbusBus() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  disconnect();
}

void ModbusBus::read(const TickTime& /*time*/, std::span<double> positions) {
  feedback_.consume(last_feedback_);
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    positions[i] = last_feedback_.positions[i];
  }
}

void ModbusBus::write(const TickTime& /*time*/, std::span<const double> positions) {
  if (!enabled_.load(std::memory_order_relaxed)) return;
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    staging_.positions[i] = positions[i];
  }
  ++staging_.sequence;
  staging_.epoch = epoch_.load(std::memory_order_relaxed);
  commands_.publish(staging_);
}

void ModbusBus::set_enabled(bool enabled) {
  // A new epoch on each enable: a command written before it, even one the I/O
  // thread has not sent yet, is never sent after it (bumpless enable).
  if (enabled && !enabled_.load(std::memory_order_relaxed)) {
    epoch_.fetch_add(1, std::memory_order_relaxed);
  }
  for (auto& b : boards_) b->wanted.store(enabled, std::memory_order_relaxed);
  enabled_.store(enabled, std::memory_order_release);
}

void ModbusBus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  const bool any = std::any_of(enabled.begin(), enabled.end(), [](auto on) { return on != 0; });
  if (!any || !enabled_.load(std::memory_order_relaxed)) {
    set_enabled(any);
    if (!any) return;
  }
  bool rising = false;
  for (auto& b : boards_) {
    bool on = true;
    for (const std::size_t a : b->actuator) {
      if (a != SIZE_MAX) on = on && a < enabled.size() && enabled[a] != 0;
    }
    rising = rising || (on && !b->wanted.load(std::memory_order_relaxed));
    b->wanted.store(on, std::memory_order_release);
    for (const std::size_t a : b->actuator) {
      if (!on && a < enabled.size()) enabled[a] = 0;  // switched off with its board
    }
  }
  // Bumpless, as on a bus enable: no command written before reaches a board
  // switched on again.
  if (rising) epoch_.fetch_add(1, std::memory_order_relaxed);
}

BusStatus ModbusBus::status() const {
  BusStatus s;
  for (const auto& b : boards_) {
    const char* r = b->reason.load(std::memory_order_acquire);
    if (r != nullptr) {
      s.fault = true;
      s.reason = r;
      break;
    }
  }
  s.frames_sent = stats_.transactions.load(std::memory_order_relaxed);
  s.errors = stats_.failures.load(std::memory_order_relaxed);
  return s;
}

std::size_t ModbusBus::boards_answered() const {
  std::size_t n = 0;
  for (const auto& b : boards_) n += b->answered.load(std::memory_order_acquire) ? 1 : 0;
  return n;
}

bool ModbusBus::command_stale(std::size_t actuator) const {
  return actuator < count_ && boards_[board_of_[actuator]]->stale.load(std::memory_order_acquire);
}

ModbusStats ModbusBus::stats() const {
  ModbusStats s;
  s.transactions = stats_.transactions.load(std::memory_order_relaxed);
  s.failures = stats_.failures.load(std::memory_order_relaxed);
  s.timeouts = stats_.timeouts.load(std::memory_order_relaxed);
  s.exceptions = stats_.exceptions.load(std::memory_order_relaxed);
  s.bad_replies = stats_.bad_replies.load(std::memory_order_relaxed);
  s.link_errors = stats_.link_errors.load(std::memory_order_relaxed);
  s.reconnects = stats_.reconnects.load(std::memory_order_relaxed);
  s.cycles = stats_.cycles.load(std::memory_order_relaxed);
  s.max_rtt_ns = stats_.max_rtt_ns.load(std::memory_order_relaxed);
  s.last_rtt_ns = stats_.last_rtt_ns.load(std::memory_order_relaxed);
  return s;
}

bool ModbusBus::connect(std::int64_t now_ns) {
  if (ctx_ != nullptr) return true;
  if (static_cast<double>(now_ns - last_connect_attempt_ns_) * 1e-9 <
      timing_.reconnect_interval_s) {
    return false;
  }
  last_connect_attempt_ns_ = now_ns;
  modbus_t* ctx = endpoint_.tcp
                      ? modbus_new_tcp(endpoint_.host.c_str(), endpoint_.port)
                      : modbus_new_rtu(endpoint_.device.c_str(), endpoint_.baud, 'N', 8, 1);
  if (ctx == nullptr) return false;
  set_modbus_timeouts(ctx, timing_);
  // No libmodbus recovery: it would sleep a whole response timeout and
  // reconnect inside a transaction. We recover ourselves, with bounds.
  modbus_set_error_recovery(ctx, MODBUS_ERROR_RECOVERY_NONE);
  if (modbus_connect(ctx) != 0) {
    stats_.link_errors.fetch_add(1, std::memory_order_relaxed);
    modbus_free(ctx);
    return false;
  }
  ctx_ = ctx;
  stats_.reconnects.fetch_add(1, std::memory_order_relaxed);
  // Push the watchdog to every board on (re)connect: the board owns the
  // timeout, so a dead host stops the head even if this thread dies too.
  for (auto& b : boards_) {
    const auto wd = static_cast<std::uint16_t>(timing_.board_watchdog_ms);
    transact(*b, [&] { return modbus_write_register(ctx_, registers_.watchdog, wd); });
    if (ctx_ == nullptr) return false;
  }
  return true;
}

void ModbusBus::disconnect() {
  if (ctx_ == nullptr) return;
  modbus_close(ctx_);
  modbus_free(ctx_);
  ctx_ = nullptr;
}

template <typename Request>
bool ModbusBus::transact(Board& board, Request&& request) {
  for (int attempt = 0; attempt <= timing_.max_retries; ++attempt) {
    if (ctx_ == nullptr) return false;
    modbus_set_slave(ctx_, board.unit);
    const std::int64_t t0 = monotonic_ns();
    const int rc = request();
    const std::int64_t t1 = monotonic_ns();
    if (rc >= 0) {
      stats_.transactions.fetch_add(1, std::memory_order_relaxed);
      const auto rtt = static_cast<std::uint64_t>(t1 - t0);
      stats_.last_rtt_ns.store(rtt, std::memory_order_relaxed);
      atomic_max(stats_.max_rtt_ns, rtt);
      board.last_ok_ns = t1;
      board.last_failure = Failure::kNone;
      board.answered.store(true, std::memory_order_release);
      return true;
    }
    const int err = errno;
    stats_.failures.fetch_add(1, std::memory_order_relaxed);
    if (err >= EMBXILFUN && err <= EMBXGTAR) {
      // The board answered and refused: repeating the request cannot help.
      stats_.exceptions.fetch_add(1, std::memory_order_relaxed);
      board.last_failure = Failure::kException;
      return false;
    }
    if (err == ETIMEDOUT) {
      stats_.timeouts.fetch_add(1, std::memory_order_relaxed);
      board.last_failure = Failure::kSilent;
      // A late reply must not be taken for the answer to the next request.
      modbus_flush(ctx_);
      continue;
    }
    if (err >= EMBBADCRC && err <= EMBBADSLAVE) {
      stats_.bad_replies.fetch_add(1, std::memory_order_relaxed);
      // Right after a timeout, a mismatched reply is most likely the late
      // answer to the timed-out request: the board is slow, not corrupt.
      if (board.last_failure != Failure::kSilent) board.last_failure = Failure::kBadReply;
      modbus_flush(ctx_);
      continue;
    }
    // Anything else is the link itself (reset, refused, device gone).
    stats_.link_errors.fetch_add(1, std::memory_order_relaxed);
    board.last_failure = Failure::kLink;
    disconnect();
    return false;
  }
  return false;
}

void ModbusBus::serve_board(Board& board, bool enabled, std::int64_t now_ns) {
  std::array<std::uint16_t, modbus_map::kInputCount> in{};
  if (enabled) {
    board.disable_confirmed = false;
    if (board.acked_sequence != current_.sequence && current_.sequence != 0 &&
        current_.epoch == io_epoch_) {
      std::array<std::uint16_t, 2 + modbus_map::kChannelsPerBoard> regs{};
      regs[0] = modbus_map::kControlEnable;
      if (board.reset_pending) regs[0] |= modbus_map::kControlFaultReset;
      // The heartbeat is the tick's own counter: if the tick stops, it stops
      // changing and the board's watchdog trips even though this thread lives.
      regs[1] = static_cast<std::uint16_t>(current_.sequence);
      for (int ch = 0; ch < board.channels; ++ch) {
        const std::size_t a = board.actuator[static_cast<std::size_t>(ch)];
        // An unused channel gets 0 (its board ignores it).
        regs[2 + static_cast<std::size_t>(ch)] =
            a == SIZE_MAX ? 0 : encodings_[a].encode_u16(current_.positions[a]);
      }
      if (transact(board, [&] {
            return modbus_write_registers(ctx_, registers_.control, 2 + board.channels,
                                          regs.data());
          })) {
        board.acked_sequence = current_.sequence;
        board.last_target_ok_ns = now_ns;
        board.reset_pending = false;
      }
    }
  } else {
    // Disabled: only CONTROL = 0, until the board confirms it, then every 100 ms.
    // No target is sent while the controller is not enabled.
    if (!board.disable_confirmed || now_ns - board.last_disable_ns > 100'000'000) {
      const std::uint16_t zero = 0;
      if (transact(board,
                   [&] { return modbus_write_registers(ctx_, registers_.control, 1, &zero); })) {
        board.disable_confirmed = true;
        board.last_disable_ns = now_ns;
      }
    }
  }
  const bool answered = transact(board, [&] {
    return modbus_read_input_registers(ctx_, registers_.status,
                                       modbus_map::kIrPosition0 + board.channels, in.data());
  });
  if (answered) {
    for (int ch = 0; ch < board.channels; ++ch) {
      const std::size_t a = board.actuator[static_cast<std::size_t>(ch)];
      if (a == SIZE_MAX) continue;
      measured_.positions[a] = encodings_[a].decode_u16(
          in[static_cast<std::size_t>(modbus_map::kIrPosition0) + static_cast<std::size_t>(ch)]);
    }
  }
  judge_board(board, monotonic_ns(), in[modbus_map::kIrStatus], answered);
}

void ModbusBus::judge_board(Board& board, std::int64_t now_ns, std::uint16_t status,
                            bool answered) {
  const double silent_s = static_cast<double>(now_ns - board.last_ok_ns) * 1e-9;
  const char* reason = nullptr;
  if (silent_s > timing_.board_timeout_s) {
    switch (board.last_failure) {
      case Failure::kException:
        reason = board.exception.c_str();
        break;
      case Failure::kBadReply:
        reason = board.bad_reply.c_str();
        break;
      case Failure::kLink:
        reason = board.link.c_str();
        break;
      default:
        reason = board.silent.c_str();
        break;
    }
  } else if (answered && (status & modbus_map::kStatusWatchdog) != 0 && board.was_on &&
             !board.reset_pending) {
    reason = board.watchdog.c_str();
  } else if (answered && (status & modbus_map::kStatusFault) != 0 && !board.reset_pending) {
    reason = board.fault.c_str();
  } else if (!answered) {
    // Still inside the timeout: keep the previous verdict.
    reason = board.reason.load(std::memory_order_relaxed);
    if (reason == board.fault.c_str() || reason == board.watchdog.c_str()) reason = nullptr;
  }
  board.reason.store(reason, std::memory_order_release);
  const bool target_late =
      board.was_on &&
      static_cast<double>(now_ns - board.last_target_ok_ns) * 1e-9 > timing_.board_timeout_s;
  board.stale.store(reason != nullptr || target_late, std::memory_order_release);
}

void ModbusBus::io_loop() {
  const auto period_ns = static_cast<std::int64_t>(timing_.cycle_period_s * 1e9);
  std::int64_t next = monotonic_ns();
  while (!stop_.load(std::memory_order_acquire)) {
    std::int64_t now = monotonic_ns();
    const bool enabled = enabled_.load(std::memory_order_acquire);
    io_epoch_ = epoch_.load(std::memory_order_relaxed);
    for (auto& b : boards_) {
      const bool on = enabled && b->wanted.load(std::memory_order_acquire);
      if (on && !b->was_on) {
        b->reset_pending = true;  // clear a latched watchdog on the enable edge
        b->last_target_ok_ns = now;
      }
      b->was_on = on;
    }
    commands_.consume(current_);
    if (connect(now)) {
      for (auto& b : boards_) serve_board(*b, b->was_on, monotonic_ns());
    } else {
      for (auto& b : boards_) {
        if (b->last_failure == Failure::kNone) b->last_failure = Failure::kLink;
        judge_board(*b, now, 0, false);
      }
    }
    feedback_.publish(measured_);
    stats_.cycles.fetch_add(1, std::memory_order_relaxed);
    if (period_ns > 0) {
      next += period_ns;
      now = monotonic_ns();
      if (next < now) next = now;  // overran: start the next cycle at once, no burst
      timespec ts{static_cast<time_t>(next / 1'000'000'000),
                  static_cast<long>(next % 1'000'000'000)};
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
    }
  }
  // Leaving: tell every board to disable (one attempt each).
  if (ctx_ != nullptr) {
    const std::uint16_t zero = 0;
    for (auto& b : boards_) {
      modbus_set_slave(ctx_, b->unit);
      modbus_write_registers(ctx_, registers_.control, 1, &zero);
    }
  }
}

}  // namespace facectl
