// The CiA 402 bus watching its drives (docs/PROTOCOLS.md, "CAN: CiA 402
// drives"): NMT state from the heartbeat, the TPDO timeout, the heartbeat
// consumer starting only once 0x1017 is set, the mode read back through
// 0x6061, pre-operational before a remap, and every SDO reply form.
#include <gtest/gtest.h>

#include "tests/drivers/can_test_rig.hpp"

namespace facectl {
namespace {

using testing::Cia402;
using testing::kDeg;
using testing::kMs;
using Form = sim::Cia402DriveSim::UploadForm;

TEST_F(Cia402, AHeartbeatReportingPreOperationalFaultsWithinOneHeartbeatPeriod) {
  options_.feedback_timeout_s = 0.2;  // so the heartbeat, not the missing TPDO, names it
  build();
  enable();
  rig_->until([] { return false; }, 50);
  drives_[1]->inject_nmt(cia402::NmtState::kPreOperational);  // as 0x1029 does
  const int ms = rig_->until([&] { return bus_->status().fault; }, 1000);
  ASSERT_GT(ms, 0);
  EXPECT_LE(ms, options_.drive_heartbeat_ms + 2);
  EXPECT_STREQ(bus_->status().reason,
               "can0 drive 2: heartbeat reports pre-operational (NMT; a communication error?)");
}

TEST_F(Cia402, AHeartbeatReportingStoppedFaultsWithinOneHeartbeatPeriod) {
  options_.feedback_timeout_s = 0.2;
  build();
  enable();
  rig_->until([] { return false; }, 50);
  drives_[2]->inject_nmt(cia402::NmtState::kStopped);
  const int ms = rig_->until([&] { return bus_->status().fault; }, 1000);
  ASSERT_GT(ms, 0);
  EXPECT_LE(ms, options_.drive_heartbeat_ms + 2);
  EXPECT_STREQ(bus_->status().reason, "can0 drive 3: heartbeat reports stopped (NMT)");
}

TEST_F(Cia402, FeedbackThatStopsWhileTheHeartbeatGoesOnFaultsAfterTenCyclesOr20Ms) {
  enable();
  rig_->until([] { return false; }, 50, 2 * kDeg);
  drives_[2]->stop_feedback(true);
  const int ms = rig_->until([&] { return bus_->status().fault; }, 1500, 2 * kDeg);
  ASSERT_GT(ms, 0) << "the position froze with no fault";
  // 1 ms ticks: ten cycles are 10 ms, so the 20 ms floor; +2 ticks to see it.
  EXPECT_GE(ms, 20);
  EXPECT_LE(ms, 22);
  EXPECT_STREQ(bus_->status().reason, "can0 drive 3: position feedback (TPDO1) stopped");
}

TEST_F(Cia402, AStallOfOurOwnLoopIsNotBlamedOnTheDrives) {
  enable();
  // 60 ms without write(): no SYNC, so no TPDO, while the drives beat on.
  rig_->until([] { return false; }, 60, 0.0, false);
  rig_->until([] { return false; }, 5);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(Cia402, TheFeedbackTimeoutIsConfigurable) {
  options_.feedback_timeout_s = 0.15;
  build();
  enable();
  drives_[0]->stop_feedback(true);
  const int ms = rig_->until([&] { return bus_->status().fault; }, 1500);
  EXPECT_GE(ms, 150);
  EXPECT_LE(ms, 152);
  EXPECT_STREQ(bus_->status().reason, "can0 drive 1: position feedback (TPDO1) stopped");
}

TEST_F(Cia402, AnIdleBusWithDrivesAtTheirDefaultHeartbeatOfZeroDoesNotFault) {
  // The drives booted (one boot-up frame each) and beat no more: 0x1017 = 0.
  rig_->until([] { return false; }, 2000, 0.0, false);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
  // Enabled, 0x1017 is the first SDO; from its confirmation the consumer runs.
  enable();
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
  drives_[0]->faults().silent = true;
  const int ms = rig_->until([&] { return bus_->status().fault; }, 1000);
  ASSERT_GT(ms, 0);
  EXPECT_STREQ(bus_->status().reason, "can0 drive 1: heartbeat lost");
  // Silent altogether: the heartbeat consumer names it, not the TPDO timeout.
  EXPECT_LE(ms, static_cast<int>(options_.heartbeat_timeout_s * 1000) + 2);
}

TEST_F(Cia402, ADriveThatDoesNotShowCspIn0x6061IsNotStarted) {
  drives_[1]->force_mode_display(1);  // profile position: it has no CSP
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 300);
  EXPECT_STREQ(bus_->status().reason,
               "can0 drive 2: 0x6061:00 reads 1, expected 8 (mode of operation: 8 is cyclic "
               "synchronous position)");
  EXPECT_EQ(drives_[1]->nmt(), cia402::NmtState::kPreOperational) << "never started";
  EXPECT_EQ(drives_[1]->state(), cia402::DriveState::kSwitchOnDisabled);
  EXPECT_EQ(drives_[1]->rpdos_received(), 0u);
}

TEST_F(Cia402, ReEnablingRemapsInPreOperational) {
  enable();
  bus_->set_enabled(false);
  rig_->until([] { return false; }, 300, 0.0, false);
  ASSERT_EQ(drives_[0]->nmt(), cia402::NmtState::kOperational);  // still, after the stop
  enable();
  for (const auto& d : drives_) EXPECT_EQ(d->mapping_refused(), 0u);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(Cia402, AnAbortedSdoNamesTheObjectAndTheAbortCode) {
  drives_[0]->refuse_object(0x607F);
  bus_->set_enabled(true);
  rig_->until([] { return false; }, 300);
  EXPECT_STREQ(bus_->status().reason,
               "can0 drive 1: SDO download 0x607F:00 aborted: 0x06020000 object does not exist");
  EXPECT_EQ(bus_->last_sdo_abort(0), 0x06020000u);
  EXPECT_EQ(drives_[0]->nmt(), cia402::NmtState::kPreOperational) << "never started";
}

class Cia402UploadForms : public Cia402, public ::testing::WithParamInterface<Form> {};

TEST_P(Cia402UploadForms, EveryLegalUploadReplyIsRead) {
  for (const auto& d : drives_) d->set_upload_form(GetParam());
  enable();
  for (const auto& d : drives_) EXPECT_EQ(d->sdo_uploads(), 1u);  // 0x6061
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

INSTANTIATE_TEST_SUITE_P(Sdo, Cia402UploadForms,
                         ::testing::Values(Form::kSized, Form::kUnsized, Form::kSegmented));

// A node that answers every SDO request with upload data (0x4F): a download
// must not count that as confirmed.
class UploadAnsweringNode final : public sim::CanDevice {
 public:
  void on_frame(const CanFrame& f, std::int64_t now_ns) override {
    if (f.id == cia402::kNmt && f.len == 2 && f.data[0] == 0x01) ++starts;
    if (f.id != cia402::kSdoRxBase + 1) return;
    CanFrame r;
    r.id = cia402::kSdoTxBase + 1;
    r.len = 8;
    r.data = {0x4F, f.data[1], f.data[2], f.data[3], 0, 0, 0, 0};
    emit(r, now_ns);
  }
  void step(std::int64_t) override {}
  int starts = 0;
};

TEST(Cia402Sdo, AnUploadReplyIsNeverADownloadConfirmation) {
  MemoryCanLink link(1024);
  UploadAnsweringNode node;
  sim::CanDeviceNetwork net(link.devices(), {&node});
  Cia402Bus bus("can0", link.host(), testing::rotary_axes(1), {0.0});
  testing::Rig<Cia402Bus> rig(bus, net, 1);
  bus.set_enabled(true);
  rig.until([] { return false; }, 100);
  EXPECT_STREQ(bus.status().reason,
               "can0 drive 1: SDO reply of the wrong kind (upload for download or back)");
  EXPECT_EQ(node.starts, 0);
}

TEST(Cia402Sdo, ADriveOnTheHostsNodeIdIsRefused) {
  MemoryCanLink link;
  CanBusOptions o;
  o.host_node = 2;
  try {
    Cia402Bus bus("can0", link.host(), testing::rotary_axes(2), {0.0, 0.0}, o);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "bus can0: actuator axis2 has node id 2, which is the host's own "
                 "(host_node)");
  }
}

}  // namespace
}  // namespace facectl
