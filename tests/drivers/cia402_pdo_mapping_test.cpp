// CiA 402: RPDO1 and TPDO1 are mapped by SDO at each enable (CiA 301
// procedure), so drives that ship another mapping work too; without the
// remap they cannot.
#include <gtest/gtest.h>

#include "drivers/can/cia402_bus.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "tests/drivers/can_test_axes.hpp"

namespace facectl {
namespace {

constexpr std::int64_t kMs = 1'000'000;

// Records the SDO requests the host sends.
class SdoSniffer final : public sim::CanDevice {
 public:
  void on_frame(const CanFrame& f, std::int64_t) override {
    if (f.id == 0x601) requests.push_back(f);
  }
  void step(std::int64_t) override {}
  std::vector<CanFrame> requests;
};

TEST(Cia402PdoMapping, TheMappingSdosFollowTheCiA301Procedure) {
  const auto sdos = cia402::pdo_mapping_sdos(5);
  ASSERT_EQ(sdos.size(), 14u);
  const std::vector<std::tuple<int, int, std::uint32_t>> expected = {
      {0x1400, 1, 0x80000205}, {0x1600, 0, 0},          {0x1600, 1, 0x60400010},
      {0x1600, 2, 0x607A0020}, {0x1600, 0, 2},          {0x1400, 2, 1},
      {0x1400, 1, 0x00000205}, {0x1800, 1, 0x80000185}, {0x1A00, 0, 0},
      {0x1A00, 1, 0x60410010}, {0x1A00, 2, 0x60640020}, {0x1A00, 0, 2},
      {0x1800, 2, 1},          {0x1800, 1, 0x00000185}};
  for (std::size_t i = 0; i < sdos.size(); ++i) {
    EXPECT_EQ(sdos[i].index, std::get<0>(expected[i])) << i;
    EXPECT_EQ(sdos[i].subindex, std::get<1>(expected[i])) << i;
    EXPECT_EQ(sdos[i].value, std::get<2>(expected[i])) << i;
  }
  // The first request on the wire: invalidate RPDO1 of node 5.
  CanFrame f;
  cia402::encode_sdo_download(5, sdos[0].index, sdos[0].subindex, sdos[0].value, sdos[0].size, f);
  EXPECT_EQ(f.id, 0x605u);
  const std::uint8_t bytes[8] = {0x23, 0x00, 0x14, 0x01, 0x05, 0x02, 0x00, 0x80};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(f.data[static_cast<std::size_t>(i)], bytes[i]) << i;
}

// Two drives that ship their PDOs mapped in the other order.
struct Remap {
  explicit Remap(bool map_pdos) {
    CanBusOptions o;
    o.map_pdos = map_pdos;
    for (int n = 1; n <= 2; ++n) {
      drives.push_back(std::make_unique<sim::Cia402DriveSim>(
          n, testing::fast_plant(), o.rotary_counts_per_rad, 0.0, /*standard_mapping=*/false));
    }
    net = std::make_unique<sim::CanDeviceNetwork>(
        link.devices(), std::vector<sim::CanDevice*>{drives[0].get(), drives[1].get(), &sniffer});
    bus = std::make_unique<Cia402Bus>("can0", link.host(), testing::rotary_axes(2),
                                      std::vector<double>(2, 0.0), o);
  }
  // 1 ms ticks until `done` or `limit` ticks; returns the ticks taken or -1.
  template <typename Done>
  int run(int limit, double target, Done done) {
    std::vector<double> meas(2), cmd(2, target);
    for (int k = 1; k <= limit; ++k) {
      now += kMs;
      bus->read({now, 0.001}, meas);
      bus->write({now, 0.001}, cmd);
      net->poll(now);
      if (done()) return k;
    }
    return -1;
  }
  bool enabled() const {
    return drives[0]->state() == cia402::DriveState::kOperationEnabled &&
           drives[1]->state() == cia402::DriveState::kOperationEnabled;
  }

  MemoryCanLink link{1024};
  std::vector<std::unique_ptr<sim::Cia402DriveSim>> drives;
  SdoSniffer sniffer;
  std::unique_ptr<sim::CanDeviceNetwork> net;
  std::unique_ptr<Cia402Bus> bus;
  std::int64_t now = 1'000 * kMs;
};

TEST(Cia402PdoMapping, DrivesShippedWithAnotherMappingAreRemappedAndFollow) {
  Remap r(true);
  r.bus->set_enabled(true);
  ASSERT_GT(r.run(300, 0.0, [&] { return r.enabled(); }), 0)
      << cia402::to_string(r.drives[0]->state());
  const double target = 10.0 * testing::kDeg;
  ASSERT_GT(r.run(1000, target,
                  [&] { return std::abs(r.drives[1]->position() - target) < 0.1 * testing::kDeg; }),
            0)
      << r.drives[1]->position();
  EXPECT_EQ(r.drives[0]->bad_pdos(), 0u);
  EXPECT_FALSE(r.bus->status().fault) << r.bus->status().reason;
  // The heartbeat first (0x1017), then the remap, before the drive's own
  // limits and mode.
  ASSERT_GE(r.sniffer.requests.size(), 22u);
  EXPECT_EQ(r.sniffer.requests[0].data[1], 0x17);
  EXPECT_EQ(r.sniffer.requests[0].data[2], 0x10);
  EXPECT_EQ(r.sniffer.requests[1].data[1], 0x00);
  EXPECT_EQ(r.sniffer.requests[1].data[2], 0x14);
  EXPECT_EQ(r.sniffer.requests[15].data[2], 0x60);  // then 0x607D:01
}

TEST(Cia402PdoMapping, WithoutTheRemapSuchDrivesNeverReachOperationEnabled) {
  Remap r(false);
  r.bus->set_enabled(true);
  EXPECT_EQ(r.run(1000, 0.0, [&] { return r.enabled(); }), -1);
  EXPECT_EQ(r.sniffer.requests.size(), 8u) << "the 7 parameter SDOs and the 0x6061 read only";
}

}  // namespace
}  // namespace facectl
