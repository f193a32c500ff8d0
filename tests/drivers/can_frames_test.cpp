// Byte-exact CAN frames, as docs/PROTOCOLS.md documents them: the custom
// board layout, the CiA 301/402 frames, and the bus budget.
#include <gtest/gtest.h>

#include <vector>

#include "drivers/protocol/can_bus_budget.hpp"
#include "drivers/protocol/cia402_frames.hpp"
#include "drivers/protocol/custom_can_frames.hpp"
#include "drivers/protocol/sdo_abort_codes.hpp"

namespace facectl {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::vector<int> bytes(const CanFrame& f) {
  return {f.data.begin(), f.data.begin() + f.len};
}

CanFrame frame(std::uint32_t id, std::vector<std::uint8_t> data) {
  CanFrame f;
  f.id = id;
  f.len = static_cast<std::uint8_t>(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) f.data[i] = data[i];
  return f;
}

using custom_can::Width;
using modbus_map::Unit;

TEST(CustomCanFrames, CommandPacksThreeInt16ChannelsAfterSequenceAndFlags) {
  const std::int32_t t[3] = {custom_can::to_counts(Unit::kRotary, Width::kInt16, 12.5 * kDeg),
                             custom_can::to_counts(Unit::kRotary, Width::kInt16, -4.0 * kDeg),
                             custom_can::to_counts(Unit::kLinear, Width::kInt16, 0.0035)};
  CanFrame f;
  custom_can::encode_command({2, 0x2A, custom_can::kFlagEnable}, Width::kInt16, t, false, f);
  EXPECT_EQ(f.id, 0x102u);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x2A, 0x01, 0xE2, 0x04, 0x70, 0xFE, 0x5E, 0x01}));
}

TEST(CustomCanFrames, Int32ChannelsAreTenThousandthsOfADegree) {
  const std::int32_t t[1] = {custom_can::to_counts(Unit::kRotary, Width::kInt32, 12.5 * kDeg)};
  CanFrame f;
  custom_can::encode_command({5, 0xFF, 0}, Width::kInt32, t, false, f);
  EXPECT_EQ(f.id, 0x105u);
  EXPECT_EQ(bytes(f), (std::vector<int>{0xFF, 0x00, 0x48, 0xE8, 0x01, 0x00}));
  EXPECT_EQ(custom_can::channels_per_frame(false, Width::kInt16), 3);
  EXPECT_EQ(custom_can::channels_per_frame(true, Width::kInt16), 31);
  EXPECT_EQ(custom_can::channels_per_frame(true, Width::kInt32), 15);
}

TEST(CustomCanFrames, CanFdFramesArePaddedToAValidLength) {
  std::vector<std::int32_t> t(12, 0x0102);
  CanFrame f;
  custom_can::encode_command({1, 7, custom_can::kFlagEnable}, Width::kInt16, t, true, f);
  EXPECT_EQ(f.len, 32);  // 2 + 24 = 26 bytes, padded to the FD length 32
  EXPECT_EQ(f.data[24], 0x02);
  EXPECT_EQ(f.data[25], 0x01);
  for (int i = 26; i < 32; ++i) EXPECT_EQ(f.data[static_cast<std::size_t>(i)], 0) << i;
  f.id = 0x181;
  const auto fb = custom_can::decode_feedback(f, Width::kInt16);
  ASSERT_TRUE(fb);
  EXPECT_EQ(fb->channels, 15);  // whole channels in the padded frame; the bus uses its 12
  EXPECT_EQ(fb->positions[11], 0x0102);
}

TEST(CustomCanFrames, FeedbackDecodesAndRejectsBadLengthsAndIds) {
  const auto fb = custom_can::decode_feedback(frame(0x182, {0x2A, 0x01, 0xE2, 0x04, 0x70, 0xFE}),
                                              Width::kInt16);
  ASSERT_TRUE(fb);
  EXPECT_EQ(fb->node, 2);
  EXPECT_EQ(fb->sequence_echo, 0x2A);
  EXPECT_EQ(fb->status, custom_can::kStatusEnabled);
  EXPECT_EQ(fb->channels, 2);
  EXPECT_EQ(fb->positions[0], 1250);
  EXPECT_EQ(fb->positions[1], -400);
  EXPECT_FALSE(custom_can::decode_feedback(frame(0x182, {0x2A, 0x01, 0xE2}), Width::kInt16));
  EXPECT_FALSE(custom_can::decode_feedback(frame(0x102, {0x2A, 0x01}), Width::kInt16));
}

TEST(Cia402Frames, NmtSyncAndRpdo1AreByteExact) {
  CanFrame f;
  cia402::encode_nmt(cia402::NmtCommand::kStart, 0, f);
  EXPECT_EQ(f.id, 0x000u);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x01, 0x00}));
  cia402::encode_sync(f);
  EXPECT_EQ(f.id, 0x080u);
  EXPECT_EQ(f.len, 0);
  cia402::encode_rpdo1(3, cia402::kCwEnableOperation, 100000, f);
  EXPECT_EQ(f.id, 0x203u);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x0F, 0x00, 0xA0, 0x86, 0x01, 0x00}));
  cia402::encode_rpdo1(3, cia402::kCwEnableOperation, -2, f);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x0F, 0x00, 0xFE, 0xFF, 0xFF, 0xFF}));
}

TEST(Cia402Frames, Tpdo1EmcyAndHeartbeatDecode) {
  const auto t = cia402::decode_tpdo1(frame(0x183, {0x37, 0x02, 0xA0, 0x86, 0x01, 0x00}));
  ASSERT_TRUE(t);
  EXPECT_EQ(t->node, 3);
  EXPECT_EQ(t->statusword, 0x0237);
  EXPECT_EQ(t->actual_position, 100000);
  EXPECT_FALSE(cia402::decode_tpdo1(frame(0x183, {0x37, 0x02})));
  const auto e = cia402::decode_emcy(frame(0x083, {0x10, 0x23, 0x04, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->node, 3);
  EXPECT_EQ(e->error_code, 0x2310);
  EXPECT_EQ(e->error_register, 0x04);
  EXPECT_FALSE(cia402::decode_emcy(frame(0x080, {})));  // that is SYNC, not an EMCY
  const auto h = cia402::decode_heartbeat(frame(0x703, {0x05}));
  ASSERT_TRUE(h);
  EXPECT_EQ(h->state, cia402::NmtState::kOperational);
}

TEST(Cia402Frames, SdoExpeditedDownloadsAndReplies) {
  CanFrame f;
  cia402::encode_sdo_download(3, 0x6060, 0, 8, 1, f);
  EXPECT_EQ(f.id, 0x603u);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x2F, 0x60, 0x60, 0x00, 0x08, 0, 0, 0}));
  cia402::encode_sdo_download(3, 0x1017, 0, 100, 2, f);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x2B, 0x17, 0x10, 0x00, 0x64, 0, 0, 0}));
  cia402::encode_sdo_download(3, 0x607D, 1, static_cast<std::uint32_t>(-50000), 4, f);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x23, 0x7D, 0x60, 0x01, 0xB0, 0x3C, 0xFF, 0xFF}));
  const auto ok = cia402::decode_sdo_reply(frame(0x583, {0x60, 0x60, 0x60, 0x00, 0, 0, 0, 0}));
  ASSERT_TRUE(ok);
  EXPECT_TRUE(ok->ok);
  EXPECT_EQ(ok->index, 0x6060);
  const auto abort =
      cia402::decode_sdo_reply(frame(0x583, {0x80, 0x60, 0x60, 0x00, 0x11, 0x00, 0x09, 0x06}));
  ASSERT_TRUE(abort);
  EXPECT_FALSE(abort->ok);
  EXPECT_EQ(abort->abort_code, 0x06090011u);
}

TEST(Cia402Frames, SdoExpeditedUploadsReadWithoutWriting) {
  CanFrame f;
  cia402::encode_sdo_upload(3, 0x1000, 0, f);
  EXPECT_EQ(f.id, 0x603u);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0}));
  // Device type 0x00020192: CiA 402 drive profile, servo.
  const auto r =
      cia402::decode_sdo_reply(frame(0x583, {0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00}));
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->upload);
  EXPECT_EQ(r->value, 0x00020192u);
  // A 2-byte upload (0x4B: 2 bytes unused) masks the rest.
  const auto w =
      cia402::decode_sdo_reply(frame(0x583, {0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0xAA, 0xBB}));
  ASSERT_TRUE(w);
  EXPECT_EQ(w->value, 0x0237u);
}

TEST(Cia402Frames, EveryLegalUploadReplyFormDecodesAndNoneIsADownloadConfirmation) {
  using cia402::SdoReplyKind;
  // Expedited with the size: 0x4F (1 byte), 0x4B (2), 0x47 (3), 0x43 (4).
  const std::vector<std::pair<int, std::uint32_t>> sized = {
      {0x4F, 0x08}, {0x4B, 0x0708}, {0x47, 0x060708}, {0x43, 0x05060708}};
  for (const auto& [cmd, value] : sized) {
    const auto r = cia402::decode_sdo_reply(
        frame(0x582, {static_cast<std::uint8_t>(cmd), 0x61, 0x60, 0x00, 8, 7, 6, 5}));
    ASSERT_TRUE(r) << cmd;
    EXPECT_EQ(r->kind, SdoReplyKind::kUploadExpedited) << cmd;
    EXPECT_EQ(r->value, value) << cmd;
    EXPECT_EQ(r->index, 0x6061);
  }
  // Expedited without the size (0x42): all four bytes, n is not valid.
  const auto unsized = cia402::decode_sdo_reply(frame(0x582, {0x42, 0x61, 0x60, 0x00, 8, 0, 0, 0}));
  ASSERT_TRUE(unsized);
  EXPECT_EQ(unsized->kind, SdoReplyKind::kUploadExpedited);
  EXPECT_EQ(unsized->value, 8u);
  // Segmented: initiate with the size (0x41), then segments with toggle and c.
  const auto init = cia402::decode_sdo_reply(frame(0x582, {0x41, 0x08, 0x10, 0x00, 17, 0, 0, 0}));
  ASSERT_TRUE(init);
  EXPECT_EQ(init->kind, SdoReplyKind::kUploadSegmented);
  EXPECT_FALSE(init->ok) << "no data yet";
  EXPECT_TRUE(init->size_indicated);
  EXPECT_EQ(init->size, 17u);
  const auto seg0 =
      cia402::decode_sdo_reply(frame(0x582, {0x00, 'f', 'a', 'c', 'e', 'c', 't', 'l'}));
  ASSERT_TRUE(seg0);
  EXPECT_EQ(seg0->kind, SdoReplyKind::kUploadSegment);
  EXPECT_FALSE(seg0->toggle);
  EXPECT_FALSE(seg0->last);
  EXPECT_EQ(seg0->segment_len, 7);
  EXPECT_EQ(seg0->segment[6], 'l');
  // t=1, n=4 (3 bytes of data), c=1.
  const auto seg1 = cia402::decode_sdo_reply(frame(0x582, {0x19, 'd', 'r', 'v', 0, 0, 0, 0}));
  ASSERT_TRUE(seg1);
  EXPECT_TRUE(seg1->toggle);
  EXPECT_TRUE(seg1->last);
  EXPECT_EQ(seg1->segment_len, 3);
  CanFrame f;
  cia402::encode_sdo_upload_segment(2, false, f);
  EXPECT_EQ(f.id, 0x602u);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x60, 0, 0, 0, 0, 0, 0, 0}));
  cia402::encode_sdo_upload_segment(2, true, f);
  EXPECT_EQ(bytes(f), (std::vector<int>{0x70, 0, 0, 0, 0, 0, 0, 0}));
  // A download confirmation carries no data, an upload is not "done".
  const auto done = cia402::decode_sdo_reply(frame(0x582, {0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0}));
  ASSERT_TRUE(done);
  EXPECT_EQ(done->kind, SdoReplyKind::kDownloadDone);
  EXPECT_FALSE(done->upload);
  // A download segment reply (0x20) answers nothing facectl sends.
  EXPECT_FALSE(cia402::decode_sdo_reply(frame(0x582, {0x20, 0, 0, 0, 0, 0, 0, 0})));
  EXPECT_STREQ(cia402::sdo_abort_text(0x06020000), "object does not exist");
  EXPECT_STREQ(cia402::sdo_abort_text(0x08000022),
               "data cannot be transferred or stored because of the present device state");
  EXPECT_STREQ(cia402::sdo_abort_text(0x12345678), "unknown abort code");
}

TEST(Cia402StateMachine, StatuswordsDecodeToTheirStates) {
  using cia402::DriveState;
  EXPECT_EQ(cia402::decode_statusword(0x0250), DriveState::kSwitchOnDisabled);
  EXPECT_EQ(cia402::decode_statusword(0x0231), DriveState::kReadyToSwitchOn);
  EXPECT_EQ(cia402::decode_statusword(0x0233), DriveState::kSwitchedOn);
  EXPECT_EQ(cia402::decode_statusword(0x0237), DriveState::kOperationEnabled);
  EXPECT_EQ(cia402::decode_statusword(0x0217), DriveState::kQuickStopActive);
  EXPECT_EQ(cia402::decode_statusword(0x021F), DriveState::kFaultReactionActive);
  EXPECT_EQ(cia402::decode_statusword(0x0218), DriveState::kFault);
}

TEST(Cia402StateMachine, ControlwordsWalkShutdownSwitchOnEnableAndResetFaultsOnAnEdge) {
  using cia402::DriveState;
  EXPECT_EQ(cia402::next_controlword(DriveState::kSwitchOnDisabled, true, 0), 0x0006);
  EXPECT_EQ(cia402::next_controlword(DriveState::kReadyToSwitchOn, true, 6), 0x0007);
  EXPECT_EQ(cia402::next_controlword(DriveState::kSwitchedOn, true, 7), 0x000F);
  EXPECT_EQ(cia402::next_controlword(DriveState::kOperationEnabled, true, 0xF), 0x000F);
  EXPECT_EQ(cia402::next_controlword(DriveState::kFault, true, 0x000F), 0x0080);
  EXPECT_EQ(cia402::next_controlword(DriveState::kFault, true, 0x0080), 0x0000);
  EXPECT_EQ(cia402::next_controlword(DriveState::kOperationEnabled, false, 0xF), 0x0000);
}

TEST(CanBusBudget, LoadUses135BitsPerFrameAndRefusesAbove70Percent) {
  const CanBusBudget cia = CanBusBudget::compute(25, 250.0, 1'000'000);
  EXPECT_NEAR(cia.load, 0.84375, 1e-12);
  EXPECT_TRUE(cia.refused());
  const CanBusBudget ok = CanBusBudget::compute(7, 500.0, 1'000'000);
  EXPECT_NEAR(ok.load, 0.4725, 1e-12);
  EXPECT_FALSE(ok.warned());
  const CanBusBudget warn = CanBusBudget::compute(8, 500.0, 1'000'000);
  EXPECT_TRUE(warn.warned());
  EXPECT_FALSE(warn.refused());
  EXPECT_NE(cia.describe("can0").find("84.4% of 1000000 bit/s (refused"), std::string::npos)
      << cia.describe("can0");
}

}  // namespace
}  // namespace facectl
