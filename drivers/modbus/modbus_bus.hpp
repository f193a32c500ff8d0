#pragma once

#include <modbus/modbus.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "control/actuator_bus.hpp"
#include "control/actuator_model.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "drivers/modbus/modbus_timing.hpp"
#include "drivers/protocol/modbus_register_map.hpp"

namespace facectl {

// Where a Modbus bus is: TCP (host, port) or RTU (serial device, baud, 8N1).
struct ModbusEndpoint {
  bool tcp = true;
  std::string host = "127.0.0.1";
  int port = 502;
  std::string device;
  int baud = 115200;

  // "host[:port]" for modbus_tcp, a device path for modbus_rtu. Throws
  // std::invalid_argument naming the bad part.
  static ModbusEndpoint parse(const std::string& type, const std::string& endpoint, long baud);
};

// Counters of the I/O thread, readable from any thread.
struct ModbusStats {
  std::uint64_t transactions = 0;  // successful request/reply pairs
  std::uint64_t failures = 0;      // attempts that failed (all kinds)
  std::uint64_t timeouts = 0;
  std::uint64_t exceptions = 0;   // exception responses
  std::uint64_t bad_replies = 0;  // CRC, length, transaction id or unit mismatches
  std::uint64_t link_errors = 0;  // connection lost or refused
  std::uint64_t reconnects = 0;
  std::uint64_t cycles = 0;
  std::uint64_t max_rtt_ns = 0;
  std::uint64_t last_rtt_ns = 0;
};

// ActuatorBus over libmodbus (TCP or RTU) to facectl's Modbus actuator boards
// (docs/PROTOCOLS.md). The tick only touches lock-free mailboxes and atomics;
// an I/O thread owns the libmodbus context and, each cycle and for each board,
// writes CONTROL, HEARTBEAT and the targets in one write-multiple-registers
// transaction and reads STATUS and positions from the input registers.
class ModbusBus final : public ActuatorBus {
 public:
  static constexpr std::size_t kMaxActuators = 64;

  // `actuators` are this bus's slice, in the controller's order; their
  // addresses place them on boards (modbus_map::place). `initial_positions`
  // are reported by read() until a board first answers. Starts the I/O thread.
  ModbusBus(std::string name, ModbusEndpoint endpoint, const std::vector<ActuatorModel>& actuators,
            const std::vector<double>& initial_positions, ModbusTiming timing = {},
            modbus_map::Addresses registers = {});
  ~ModbusBus() override;
  ModbusBus(const ModbusBus&) = delete;
  ModbusBus& operator=(const ModbusBus&) = delete;

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  // CONTROL is per board (unit): a board is on only while every actuator on
  // it is; a board switched off gets CONTROL = 0 and no targets, as on a
  // disabled bus, while the others run.
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;

  // True when the actuator's board has not confirmed a target write within
  // board_timeout_s: the board holds (or has relaxed from) an old command.
  bool command_stale(std::size_t actuator) const;
  std::size_t board_count() const { return boards_.size(); }
  // Boards that have answered at least one transaction since start-up.
  std::size_t boards_answered() const;
  ModbusStats stats() const;

 private:
  struct Command {
    std::array<double, kMaxActuators> positions{};
    std::uint64_t sequence = 0;
    std::uint32_t epoch = 0;  // enable count when written: older ones are never sent
  };
  struct Feedback {
    std::array<double, kMaxActuators> positions{};
  };
  enum class Failure : int { kNone, kSilent, kException, kBadReply, kLink };
  struct Board {
    int unit = 0;
    std::vector<std::size_t> actuator;  // channel -> actuator index (in this bus)
    int channels = 0;                   // highest used channel + 1
    // I/O thread only.
    std::uint64_t acked_sequence = 0;
    std::int64_t last_ok_ns = 0;
    std::int64_t last_target_ok_ns = 0;
    std::int64_t last_disable_ns = 0;
    bool reset_pending = false;
    bool disable_confirmed = false;
    bool was_on = false;  // enabled on the previous cycle
    Failure last_failure = Failure::kNone;
    // Static reasons, built once (BusStatus::reason must outlive the call).
    std::string silent, exception, bad_reply, link, fault, watchdog;
    // Shared with the tick.
    std::atomic<const char*> reason{nullptr};
    std::atomic<bool> stale{true};
    std::atomic<bool> answered{false};
    std::atomic<bool> wanted{false};  // enabled by the controller (every channel on)
  };

  void io_loop();
  bool connect(std::int64_t now_ns);
  void disconnect();
  void serve_board(Board& board, bool enabled, std::int64_t now_ns);
  template <typename Request>
  bool transact(Board& board, Request&& request);
  void judge_board(Board& board, std::int64_t now_ns, std::uint16_t status, bool answered);

  std::string name_;
  ModbusEndpoint endpoint_;
  ModbusTiming timing_;
  modbus_map::Addresses registers_;
  std::size_t count_ = 0;
  std::vector<WireEncoding> encodings_;  // per actuator
  std::vector<std::size_t> board_of_;    // per actuator
  std::vector<std::unique_ptr<Board>> boards_;

  // Tick side.
  LatestValueMailbox<Command> commands_;
  LatestValueMailbox<Feedback> feedback_;
  Command staging_;
  Feedback last_feedback_;
  std::atomic<bool> enabled_{false};
  std::atomic<std::uint32_t> epoch_{0};  // +1 on every enable

  // I/O thread side.
  modbus_t* ctx_ = nullptr;
  std::int64_t last_connect_attempt_ns_ = -1'000'000'000'000;
  Command current_;
  Feedback measured_;
  std::uint32_t io_epoch_ = 0;

  struct AtomicStats {
    std::atomic<std::uint64_t> transactions{0}, failures{0}, timeouts{0}, exceptions{0},
        bad_replies{0}, link_errors{0}, reconnects{0}, cycles{0}, max_rtt_ns{0}, last_rtt_ns{0};
  } stats_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl
