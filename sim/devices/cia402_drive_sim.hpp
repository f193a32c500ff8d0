#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>

#include "drivers/protocol/cia402_counts.hpp"
#include "drivers/protocol/cia402_frames.hpp"
#include "sim/devices/can_device.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl::sim {

// A simulated CiA 402 servo drive: NMT, SDO expedited download of the objects
// facectl writes, SDO upload of a few it reads (in the reply form a test
// picks), RPDO1/TPDO1 on SYNC in cyclic synchronous position mode, the
// controlword state machine, heartbeat producer and consumer (its
// communication watchdog), EMCY on faults, and its own position limits.
class Cia402DriveSim final : public CanDevice {
 public:
  // `standard_mapping`: whether RPDO1/TPDO1 ship mapped as facectl uses them
  // (controlword + target position; statusword + position actual). If not,
  // they ship in the other order, and only an SDO remap makes them usable.
  Cia402DriveSim(int node, ServoPlantParams plant, cia402::DriveCounts counts, double initial_si,
                 bool standard_mapping = true);
  // Counts per rad (or m) with no offset, as a bus's counts_per_rev.
  Cia402DriveSim(int node, ServoPlantParams plant, double counts_per_si, double initial_si,
                 bool standard_mapping = true)
      : Cia402DriveSim(node, plant, cia402::DriveCounts{counts_per_si, 0.0}, initial_si,
                       standard_mapping) {}

  void on_frame(const CanFrame& f, std::int64_t now_ns) override;
  void step(std::int64_t now_ns) override;

  // Raises a drive fault with this EMCY error code (e.g. 0x2310 overcurrent).
  void inject_fault(std::uint16_t emcy_code) { injected_.store(emcy_code); }
  // Changes its NMT state on its own, as 0x1029 does on a communication
  // error (to pre-operational or stopped); its heartbeat reports it.
  void inject_nmt(cia402::NmtState s) { injected_nmt_.store(static_cast<int>(s)); }
  // Stops (or resumes) its TPDO1 while everything else goes on.
  void stop_feedback(bool stop) { feedback_stopped_.store(stop); }
  // Reports this mode in 0x6061 whatever 0x6060 says (a drive without CSP).
  void force_mode_display(int mode) { forced_mode_.store(mode); }
  // How it answers an upload: expedited with the size (0x4F/0x4B/0x43),
  // expedited without it (0x42), or segmented (0x41, then segments).
  enum class UploadForm { kSized, kUnsized, kSegmented };
  void set_upload_form(UploadForm form) { upload_form_.store(form); }
  // Aborts every download to this index with 0x06020000 (object does not exist).
  void refuse_object(std::uint16_t index) { refused_index_.store(index); }

  // Test observation (thread-safe).
  cia402::DriveState state() const;
  cia402::NmtState nmt() const;
  double position() const;  // true plant position, SI
  std::uint64_t rpdos_received() const { return rpdos_.load(); }
  std::uint64_t sdo_writes() const { return sdo_writes_.load(); }
  std::int32_t limit_min() const { return limit_min_.load(); }
  std::int32_t limit_max() const { return limit_max_.load(); }
  int mode() const { return mode_.load(); }
  std::uint64_t bad_pdos() const { return bad_pdos_.load(); }
  std::uint64_t sdo_uploads() const { return sdo_uploads_.load(); }
  std::uint64_t mapping_refused() const { return mapping_refused_.load(); }
  std::uint16_t last_controlword() const { return last_cw_.load(); }
  // Times the controlword changed to quick stop (0x0002).
  std::uint64_t quick_stops() const { return quick_stops_.load(); }

 private:
  void fault(std::uint16_t code, std::int64_t now_ns);
  std::uint16_t statusword() const;
  void apply_controlword(std::uint16_t cw);
  // A PDO's communication (0x14xx / 0x18xx) and mapping (0x16xx / 0x1Axx) objects.
  struct Pdo {
    std::uint32_t cob = 0;  // bit 31: invalid
    int type = 1;
    int count = 2;
    std::array<std::uint32_t, 8> map{};
    int bytes() const;
  };
  bool write_pdo_object(Pdo& pdo, bool mapping, std::uint8_t sub, std::uint32_t v);
  void upload(std::uint16_t index, std::uint8_t sub, CanFrame& r, std::int64_t now_ns);
  void upload_segment(const CanFrame& f, CanFrame& r, std::int64_t now_ns);

  const int node_;
  const cia402::DriveCounts counts_;
  mutable std::mutex mutex_;
  ServoPlant plant_;
  cia402::NmtState nmt_ = cia402::NmtState::kPreOperational;
  cia402::DriveState ds_ = cia402::DriveState::kSwitchOnDisabled;
  std::uint16_t controlword_ = 0;
  std::int32_t pending_target_ = 0;
  bool booted_ = false;
  int heartbeat_ms_ = 0;         // 0x1017
  int consumer_node_ = 0;        // 0x1016:01 bits 16..22
  int consumer_ms_ = 0;          // 0x1016:01 bits 0..15
  bool consumer_armed_ = false;  // active from the first heartbeat it sees
  std::int64_t last_host_heartbeat_ns_ = 0;
  std::int64_t last_heartbeat_sent_ns_ = 0;
  std::atomic<std::int32_t> limit_min_{-2147483647}, limit_max_{2147483647};
  std::atomic<int> mode_{0};
  std::atomic<std::uint16_t> injected_{0};
  std::atomic<int> injected_nmt_{-1}, forced_mode_{-1}, refused_index_{-1};
  std::atomic<bool> feedback_stopped_{false};
  std::atomic<UploadForm> upload_form_{UploadForm::kSized};
  std::atomic<std::uint16_t> last_cw_{0};
  std::atomic<std::uint64_t> rpdos_{0}, sdo_writes_{0}, bad_pdos_{0}, sdo_uploads_{0},
      mapping_refused_{0}, quick_stops_{0};
  std::array<std::uint8_t, 4> segment_data_{};  // a segmented upload in progress
  int segment_len_ = 0;
  bool segment_toggle_ = false;
  Pdo rpdo_, tpdo_;
};

}  // namespace facectl::sim
