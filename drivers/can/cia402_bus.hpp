#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "control/actuator_bus.hpp"
#include "control/actuator_model.hpp"
#include "drivers/can/can_bus_health.hpp"
#include "drivers/can/can_bus_options.hpp"
#include "drivers/can/can_transport.hpp"
#include "drivers/protocol/can_bus_budget.hpp"
#include "drivers/protocol/cia402_counts.hpp"
#include "drivers/protocol/cia402_frames.hpp"

namespace facectl {

// ActuatorBus for CiA 402 servo drives in cyclic synchronous position mode,
// one drive per actuator (node id = the actuator's address, 1..127). Runs in
// the tick: every call is non-blocking and allocation-free.
//
// Enabling, per drive (docs/PROTOCOLS.md, "Start-up"): NMT pre-operational,
// SDO writes (its heartbeat first, the PDO mapping, its own position and
// velocity limits, mode CSP read back through 0x6061, its watchdog on our
// heartbeat, fault on connection loss), NMT start, then the controlword walk
// shutdown -> switch on -> enable operation, resetting a fault on the way.
// Each cycle: one RPDO1 per drive, then SYNC; TPDO1 brings statusword and
// actual position back. A drive is a FAULT when its heartbeat stops or
// reports another NMT state than operational, or its TPDO1 stops.
// Disabling sends quick stop, then disable voltage, then nothing at all; the
// drives' watchdogs take over.
class Cia402Bus final : public ActuatorBus {
 public:
  Cia402Bus(std::string name, CanTransport& transport, const std::vector<ActuatorModel>& actuators,
            const std::vector<double>& initial_positions, CanBusOptions options = {});

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  // A drive switched off while others run gets controlword 0 (disable
  // voltage: torque off) and its own position as target, every cycle.
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;

  // Frames on the wire per bus cycle: SYNC, one RPDO and one TPDO per drive,
  // plus the heartbeats (ours and the drives'), rounded up.
  CanBusBudget budget(double tick_hz, long bitrate) const;
  cia402::DriveState drive_state(std::size_t actuator) const;
  std::uint16_t last_emcy(std::size_t actuator) const;
  std::uint32_t last_sdo_abort(std::size_t actuator) const;
  std::uint64_t bad_frames() const { return bad_frames_.load(std::memory_order_relaxed); }

 private:
  enum class Phase { kIdle, kPreOp, kSdo, kStart, kPdo };
  enum class Sdo { kIdle, kDownload, kUpload, kSegments };
  struct Drive {
    int node = 0;
    cia402::DriveCounts counts;          // position counts (docs/PROTOCOLS.md)
    std::vector<cia402::SdoWrite> sdos;  // built once
    double position = 0.0;               // SI, last TPDO
    std::uint16_t statusword = 0;
    std::uint16_t controlword = 0;
    Phase phase = Phase::kIdle;
    std::size_t sdo_next = 0;
    Sdo sdo = Sdo::kIdle;  // the transfer in flight
    bool sdo_toggle = false;
    std::uint32_t sdo_value = 0, sdo_bytes = 0;  // segmented upload so far
    std::int64_t sdo_sent_ns = 0;
    std::int64_t pdo_since_ns = 0;
    std::int64_t last_tpdo_ns = 0;
    std::uint64_t tpdo_sync = 0;  // syncs_ at the last TPDO
    bool reached_enabled = false;
    bool wanted = false;              // enabled by the controller (per actuator)
    std::int64_t stop_since_ns = -1;  // quick stop sent since (-1: not yet)
    bool stop_done = false;           // disable voltage sent
    bool heartbeat_set = false;       // 0x1017 confirmed: the consumer runs
    std::int64_t last_heartbeat_ns = 0;
    std::uint16_t emcy = 0;
    std::uint32_t sdo_abort = 0;
    std::atomic<const char*> fault{nullptr};
    std::string who, lost, emergency, drive_fault, sdo_timeout, stuck, rebooted, preop, stopped,
        no_feedback, wrong_reply, bad_upload;
    std::array<char, 192> detail{};  // a reason with numbers in it, formatted once
  };

  void handle(const CanFrame& f, std::int64_t now_ns);
  void handle_sdo(Drive& d, const cia402::SdoReply& r, std::int64_t now_ns);
  void sdo_done(Drive& d, std::uint32_t uploaded, std::int64_t now_ns);
  void fail_detail(Drive& d, const char* format, ...);
  void send(const CanFrame& f) { health_.on_send(transport_.send(f)); }
  void step_drive(Drive& d, double target, std::int64_t now_ns);
  void stop_drive(Drive& d, std::int64_t now_ns);
  void stop_cycle(std::int64_t now_ns);
  void end_of_cycle(std::int64_t now_ns);
  void restart_drive(Drive& d, bool wanted);

  std::string name_;
  CanTransport& transport_;
  CanBusOptions options_;
  std::vector<std::unique_ptr<Drive>> drives_;
  CanBusHealth health_;
  bool enabled_ = false;
  bool stopping_ = false;  // disabled, quick stop and disable voltage under way
  std::uint64_t cycle_ = 0;
  std::int64_t now_ns_ = 0;  // the last tick's time
  std::int64_t feedback_timeout_ns_ = 0;
  std::uint64_t syncs_ = 0;  // SYNC frames sent
  std::int64_t last_host_heartbeat_ns_ = 0;
  std::atomic<std::uint64_t> bad_frames_{0};
  CanFrame frame_;
};

}  // namespace facectl
