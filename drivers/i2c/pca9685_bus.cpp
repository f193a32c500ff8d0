#include "drivers/i2c/pca9685_bus.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include "control/clock.hpp"

namespace facectl {

namespace {

void sleep_until(std::int64_t t_ns) {
  timespec ts{static_cast<time_t>(t_ns / 1'000'000'000), static_cast<long>(t_ns % 1'000'000'000)};
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

std::string hex(int v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02x", v & 0xFF);
  return buf;
}

}  // namespace

Pca9685Bus::Pca9685Bus(std::string name, std::unique_ptr<I2cTransport> transport,
                       const std::vector<ActuatorModel>& actuators,
                       const std::vector<double>& initial_positions, Pca9685Options options)
    : name_(std::move(name)),
      transport_(std::move(transport)),
      options_(std::move(options)),
      prescale_(pca9685::prescale_for(options_.pwm_hz)),
      actual_hz_(pca9685::frequency_of(prescale_)),
      count_(actuators.size()) {
  if (count_ > kMaxActuators) {
    throw std::invalid_argument("bus " + name_ + ": " + std::to_string(count_) +
                                " actuators, at most " + std::to_string(kMaxActuators));
  }
  if (initial_positions.size() != count_) {
    throw std::invalid_argument("bus " + name_ + ": one initial position per actuator");
  }
  if (options_.boards.empty()) throw std::invalid_argument("bus " + name_ + ": no boards");
  for (const int address : options_.boards) {
    if (address < pca9685::kFirstAddress || address > pca9685::kLastAddress) {
      throw std::invalid_argument("bus " + name_ + ": board address " + hex(address) +
                                  " outside 0x40..0x7f");
    }
    auto b = std::make_unique<Board>();
    b->address = address;
    b->actuator.fill(SIZE_MAX);
    const std::string who = name_ + " board " + hex(address) + " on " + transport_->where();
    b->silent = who + ": not answering (no ACK or bus error)";
    b->lost = who + ": lost its set-up (MODE1 changed: reset or brown-out); restart to re-arm";
    boards_.push_back(std::move(b));
  }
  const int n_boards = static_cast<int>(boards_.size());
  for (std::size_t i = 0; i < count_; ++i) {
    const ActuatorModel& a = actuators[i];
    if (a.encoding.raw != ActuatorEncoding::Raw::kUint16) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name +
                                  ": a PCA9685 needs encoding raw: uint16 (pulse in µs)");
    }
    Pca9685Placement p;
    try {
      p = pca9685_place(a.address, n_boards);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name + ": " + e.what());
    }
    Board& board = *boards_[static_cast<std::size_t>(p.board)];
    std::size_t& slot = board.actuator[static_cast<std::size_t>(p.channel)];
    if (slot != SIZE_MAX) {
      throw std::invalid_argument("bus " + name_ + ": actuators " + actuators[slot].name + " and " +
                                  a.name + " share address " + std::to_string(a.address));
    }
    slot = i;
    encodings_.emplace_back(a.kind, a.encoding);
    staging_.positions[i] = initial_positions[i];
  }
  current_ = staging_;
  thread_ = std::thread([this] { io_loop(); });
}

Pca9685Bus::~Pca9685Bus() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
}

void Pca9685Bus::read(const TickTime& /*time*/, std::span<double> positions) {
  // No feedback from a PCA9685: the last commanded position.
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    positions[i] = staging_.positions[i];
  }
}

void Pca9685Bus::write(const TickTime& /*time*/, std::span<const double> positions) {
  if (on_mask_.load(std::memory_order_relaxed) == 0) return;
  for (std::size_t i = 0; i < count_ && i < positions.size(); ++i) {
    staging_.positions[i] = positions[i];
  }
  ++staging_.sequence;
  commands_.publish(staging_);
}

void Pca9685Bus::set_enabled(bool enabled) {
  const std::uint64_t all = count_ == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << count_) - 1;
  on_mask_.store(enabled ? all : 0, std::memory_order_release);
}

void Pca9685Bus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  std::uint64_t mask = 0;
  for (std::size_t i = 0; i < count_ && i < enabled.size(); ++i) {
    if (enabled[i] != 0) mask |= std::uint64_t{1} << i;
  }
  on_mask_.store(mask, std::memory_order_release);
}

BusStatus Pca9685Bus::status() const {
  BusStatus s;
  for (const auto& b : boards_) {
    const char* r = b->reason.load(std::memory_order_acquire);
    if (r != nullptr) {
      s.fault = true;
      s.reason = r;
      break;
    }
  }
  s.frames_sent = transfers_.load(std::memory_order_relaxed);
  s.errors = failures_.load(std::memory_order_relaxed);
  return s;
}

std::size_t Pca9685Bus::boards_ready() const {
  std::size_t n = 0;
  for (const auto& b : boards_) n += b->ready_flag.load(std::memory_order_acquire) ? 1 : 0;
  return n;
}

int Pca9685Bus::count(int rc) {
  (rc < 0 ? failures_ : transfers_).fetch_add(1, std::memory_order_relaxed);
  return rc;
}

const char* Pca9685Bus::describe_mismatch(Board& board, int prescale, int mode1) {
  // Written once: the board is latched and never set up again.
  board.mismatch = name_ + " board " + hex(board.address) + " on " + transport_->where() +
                   ": reads back PRE_SCALE " + hex(prescale) + ", MODE1 " + hex(mode1) +
                   "; expected " + hex(prescale_) + ", " + hex(pca9685::kMode1AutoIncrement) +
                   " (not a PCA9685, or an external clock?)";
  return board.mismatch.c_str();
}

// Data sheet 7.3.1.1 and 7.3.5: PRE_SCALE only takes a write while SLEEP is
// set, and the oscillator needs 500 µs after SLEEP is cleared.
bool Pca9685Bus::init_board(Board& board) {
  using namespace pca9685;
  auto& t = *transport_;
  const int a = board.address;
  const bool written =
      count(t.write_byte(a, kMode1, kMode1Sleep)) >= 0 &&  // asleep, no ALLCALL, no AI
      count(t.write_byte(a, kMode2, kMode2OutDrv)) >= 0 &&
      // Every output off before the oscillator runs (no auto-increment yet:
      // one register at a time).
      count(t.write_byte(a, kAllLedOnL, 0)) >= 0 &&
      count(t.write_byte(a, kAllLedOnL + 1, 0)) >= 0 &&
      count(t.write_byte(a, kAllLedOnL + 2, 0)) >= 0 &&
      count(t.write_byte(a, kAllLedOffH, kLedFull)) >= 0 &&
      count(t.write_byte(a, kPreScale, static_cast<std::uint8_t>(prescale_))) >= 0 &&
      count(t.write_byte(a, kMode1, 0)) >= 0;  // wake
  if (!written) return false;
  sleep_until(monotonic_ns() + static_cast<std::int64_t>(kWakeUpS * 1e9));
  if (count(t.write_byte(a, kMode1, kMode1AutoIncrement)) < 0) return false;
  const int prescale = count(t.read_byte(a, kPreScale));
  const int mode1 = count(t.read_byte(a, kMode1));
  if (prescale < 0 || mode1 < 0) return false;
  // RESTART may read 1 after a wake from a sleep with outputs running: harmless.
  if (prescale != prescale_ || (mode1 & ~kMode1Restart) != kMode1AutoIncrement) {
    board.latched = true;
    board.reason.store(describe_mismatch(board, prescale, mode1), std::memory_order_release);
    return false;
  }
  board.written.fill(full_off_registers());
  board.ready = true;
  board.ready_flag.store(true, std::memory_order_release);
  board.reason.store(nullptr, std::memory_order_release);
  return true;
}

void Pca9685Bus::serve_board(Board& board, std::uint64_t on_mask) {
  using namespace pca9685;
  std::array<LedRegisters, kChannels> want = board.written;
  int lo = kChannels, hi = -1;
  for (int ch = 0; ch < kChannels; ++ch) {
    const std::size_t a = board.actuator[static_cast<std::size_t>(ch)];
    if (a == SIZE_MAX) continue;
    const bool on = (on_mask >> a) & 1U;
    const auto pulse = static_cast<double>(encodings_[a].encode(current_.positions[a]));
    want[static_cast<std::size_t>(ch)] =
        on ? pulse_registers(pulse, actual_hz_) : full_off_registers();
    if (want[static_cast<std::size_t>(ch)] != board.written[static_cast<std::size_t>(ch)]) {
      lo = std::min(lo, ch);
      hi = std::max(hi, ch);
    }
  }
  bool ok = true;
  // The changed span, up to 8 channels (32 bytes, one SMBus block) per transfer.
  for (int first = lo; ok && first <= hi; first += 8) {
    const int n = std::min(8, hi - first + 1);
    std::array<std::uint8_t, I2cTransport::kMaxBlock> bytes{};
    for (int k = 0; k < n; ++k) {
      const auto& r = want[static_cast<std::size_t>(first + k)];
      std::copy(r.begin(), r.end(), bytes.begin() + 4 * k);
    }
    ok = count(transport_->write_block(board.address, led_on_l(first),
                                       std::span(bytes.data(), static_cast<std::size_t>(4 * n)))) >=
         0;
    if (ok) {
      for (int k = 0; k < n; ++k) {
        board.written[static_cast<std::size_t>(first + k)] =
            want[static_cast<std::size_t>(first + k)];
      }
    }
  }
  // MODE1 back every cycle: the board answers, and has not reset (a reset
  // board sleeps with its outputs off, MODE1 = 0x11).
  const int mode1 = ok ? count(transport_->read_byte(board.address, kMode1)) : -1;
  if (mode1 < 0) {
    board.reason.store(board.silent.c_str(), std::memory_order_release);
  } else if ((mode1 & ~kMode1Restart) != kMode1AutoIncrement) {
    board.latched = true;
    board.ready_flag.store(false, std::memory_order_release);
    board.reason.store(board.lost.c_str(), std::memory_order_release);
  } else {
    board.reason.store(nullptr, std::memory_order_release);
  }
}

void Pca9685Bus::io_loop() {
  const auto period_ns = static_cast<std::int64_t>(pca9685_cycle_period_s(options_) * 1e9);
  std::int64_t next = monotonic_ns();
  while (!stop_.load(std::memory_order_acquire)) {
    const std::int64_t now = monotonic_ns();
    commands_.consume(current_);
    const std::uint64_t on_mask = on_mask_.load(std::memory_order_acquire);
    for (auto& bp : boards_) {
      Board& b = *bp;
      if (b.latched) continue;
      if (!b.ready) {
        if (now < b.next_init_ns) continue;
        b.next_init_ns = now + static_cast<std::int64_t>(options_.retry_init_s * 1e9);
        if (!init_board(b)) {
          if (!b.latched) b.reason.store(b.silent.c_str(), std::memory_order_release);
          continue;
        }
      }
      serve_board(b, on_mask);
    }
    cycles_.fetch_add(1, std::memory_order_relaxed);
    next += period_ns;
    const std::int64_t after = monotonic_ns();
    if (next < after) next = after;  // overran: no burst to catch up
    sleep_until(next);
  }
  // Leaving: every output off (limp), one attempt per board.
  for (auto& b : boards_) {
    if (!b->ready || b->latched) continue;
    transport_->write_byte(b->address, pca9685::kAllLedOffH, pca9685::kLedFull);
  }
}

}  // namespace facectl
