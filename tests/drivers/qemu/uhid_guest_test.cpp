// Runs inside the QEMU guest: a virtual gamepad made through /dev/uhid (the
// uhid module), read by HidGamepad through hidapi's hidraw backend, as a real
// USB or Bluetooth pad would be. Covers enumeration, opening by vendor and
// product, decoding, draining a backlog, and hot-plug; and puppeteering from
// it with record mode, whose show file loads back. And a uhid device with a
// real DualShock 4's report descriptor, whose layout is read back through
// the kernel (HIDIOCGRDESC, sysfs) and decodes its reports.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/input.h>
#include <linux/uhid.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <span>
#include <thread>

#include "control/clock.hpp"
#include "drivers/hid/gamepad_descriptor_layout.hpp"
#include "drivers/hid/hid_gamepad.hpp"
#include "firmware-host/inputs/gamepad_puppeteer.hpp"
#include "firmware-host/inputs/show.hpp"

namespace facectl {
namespace {

constexpr std::uint16_t kVendor = 0x1209;  // pid.codes test vendor
constexpr std::uint16_t kProduct = 0xFACE;

// Game pad: X and Y as int8 (-127..127), then 8 buttons, no report id.
constexpr std::uint8_t kDescriptor[] = {
    0x05, 0x01, 0x09, 0x05, 0xA1, 0x01,              // Generic Desktop, Game Pad, Application
    0x09, 0x30, 0x09, 0x31, 0x15, 0x81, 0x25, 0x7F,  // X, Y, logical -127..127
    0x75, 0x08, 0x95, 0x02, 0x81, 0x02,              // 2 x 8 bits, Input (Data,Var,Abs)
    0x05, 0x09, 0x19, 0x01, 0x29, 0x08, 0x15, 0x00, 0x25, 0x01,  // Buttons 1..8, 0..1
    0x75, 0x01, 0x95, 0x08, 0x81, 0x02,                          // 8 x 1 bit, Input
    0xC0};

// Sony DualShock 4 over USB (tests/drivers/hid_descriptors/SOURCES.md),
// made into a C array by tests/CMakeLists.txt.
constexpr std::uint8_t kDualShock4Descriptor[] = {
#include "sony_ds4_usb.inc"
};

class VirtualGamepad {
 public:
  explicit VirtualGamepad(std::span<const std::uint8_t> descriptor = kDescriptor,
                          std::uint16_t product = kProduct)
      : descriptor_(descriptor), product_(product) {
    fd_ = open("/dev/uhid", O_RDWR | O_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error("/dev/uhid: " + std::string(std::strerror(errno)));
    create();
  }
  ~VirtualGamepad() {
    destroy();
    close(fd_);
  }
  void create() {
    uhid_event ev{};
    ev.type = UHID_CREATE2;
    std::snprintf(reinterpret_cast<char*>(ev.u.create2.name), sizeof ev.u.create2.name,
                  "facectl virtual gamepad");
    std::memcpy(ev.u.create2.rd_data, descriptor_.data(), descriptor_.size());
    ev.u.create2.rd_size = static_cast<std::uint16_t>(descriptor_.size());
    // Bluetooth: hidapi's hidraw backend lists a USB-bus device only if it
    // has a real USB parent, which a uhid device has not.
    ev.u.create2.bus = BUS_BLUETOOTH;
    ev.u.create2.vendor = kVendor;
    ev.u.create2.product = product_;
    write_event(ev);
  }
  void destroy() {
    uhid_event ev{};
    ev.type = UHID_DESTROY;
    write_event(ev);
  }
  void report(std::int8_t x, std::int8_t y, std::uint8_t buttons) {
    uhid_event ev{};
    ev.type = UHID_INPUT2;
    ev.u.input2.size = 3;
    ev.u.input2.data[0] = static_cast<std::uint8_t>(x);
    ev.u.input2.data[1] = static_cast<std::uint8_t>(y);
    ev.u.input2.data[2] = buttons;
    write_event(ev);
  }
  void raw_report(std::span<const std::uint8_t> bytes) {
    uhid_event ev{};
    ev.type = UHID_INPUT2;
    ev.u.input2.size = static_cast<std::uint16_t>(bytes.size());
    std::memcpy(ev.u.input2.data, bytes.data(), bytes.size());
    write_event(ev);
  }

 private:
  void write_event(const uhid_event& ev) {
    if (::write(fd_, &ev, sizeof ev) != static_cast<ssize_t>(sizeof ev)) {
      throw std::runtime_error("uhid write: " + std::string(std::strerror(errno)));
    }
  }
  int fd_ = -1;
  std::span<const std::uint8_t> descriptor_;
  std::uint16_t product_;
};

GamepadLayout layout() {
  GamepadLayout l;
  l.axes = {{"x", 0, 8, true, -127, 127}, {"y", 1, 8, true, -127, 127}};
  for (int b = 0; b < 8; ++b) l.buttons.push_back({"b" + std::to_string(b), 2, b});
  return l;
}

template <typename Pred>
bool wait_for(Pred pred, int ms) {
  for (int i = 0; i < ms; ++i) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

TEST(Uhid, AVirtualGamepadIsEnumeratedReadDecodedAndSurvivesHotPlug) {
  VirtualGamepad pad;
  std::vector<HidDeviceInfo> found;
  ASSERT_TRUE(wait_for([&] { return !(found = enumerate_hid(kVendor, kProduct)).empty(); }, 3000))
      << "hidapi did not list the uhid gamepad";
  std::printf("[uhid] hidapi lists %s %04x:%04x '%s'\n", found[0].path.c_str(), found[0].vendor,
              found[0].product, found[0].product_name.c_str());

  HidGamepad gp({"", kVendor, kProduct}, layout());
  GamepadState s;
  ASSERT_TRUE(wait_for([&] { return gp.latest(s) && s.connected; }, 3000)) << "not opened";
  const std::int64_t sent = monotonic_ns();
  pad.report(127, -127, 0x05);
  ASSERT_TRUE(wait_for([&] { return gp.latest(s) && s.reports > 0; }, 1000)) << "no report";
  EXPECT_DOUBLE_EQ(s.axes[0], 1.0);
  EXPECT_DOUBLE_EQ(s.axes[1], -1.0);
  EXPECT_EQ(s.buttons, 0x05u);
  std::printf("[uhid] report 7F 81 05 -> x %+.2f y %+.2f buttons 0x%02X, %.2f ms after the write\n",
              s.axes[0], s.axes[1], s.buttons, static_cast<double>(s.received_ns - sent) * 1e-6);

  // A burst: the reader drains it, and the newest report wins.
  for (int i = 0; i < 50; ++i) pad.report(static_cast<std::int8_t>(i), 0, 0);
  pad.report(-127, 127, 0x80);
  ASSERT_TRUE(wait_for(
      [&] {
        gp.latest(s);
        return s.buttons == 0x80u;
      },
      1000));
  EXPECT_DOUBLE_EQ(s.axes[0], -1.0);
  EXPECT_EQ(gp.bad_reports(), 0u);

  // Unplug, then plug back in.
  pad.destroy();
  ASSERT_TRUE(wait_for([&] { return gp.latest(s) && !s.connected; }, 2000)) << "unplug not seen";
  pad.create();
  ASSERT_TRUE(wait_for([&] { return gp.latest(s) && s.connected; }, 3000)) << "replug not seen";
  EXPECT_EQ(gp.opens(), 2u);
  pad.report(0, 64, 0x01);
  ASSERT_TRUE(wait_for(
      [&] {
        gp.latest(s);
        return s.buttons == 0x01u;
      },
      1000));
  std::printf("[uhid] unplugged and plugged back: opened %llu times, reading again (y %+.2f)\n",
              static_cast<unsigned long long>(gp.opens()), s.axes[1]);
}

TEST(Uhid, PuppeteeringFromTheVirtualGamepadRecordsAShowThatLoadsBack) {
  VirtualGamepad pad;
  ASSERT_TRUE(wait_for([&] { return !enumerate_hid(kVendor, kProduct).empty(); }, 3000));
  HidGamepad gp({"", kVendor, kProduct}, layout());
  // A small head: two muscles, then the mandible and the rigid DOFs.
  const FaceLayout face({"zygomaticus_major_l", "zygomaticus_major_r"});
  std::array<double, kMaxFaceSignals> neutral{};
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  GamepadMapping mapping(
      {{GamepadTerm::Source::kAxis, 1, face.jaw_pitch(), 9 * kDeg, 9 * kDeg, 0.0},
       {GamepadTerm::Source::kButton, 0, 0, 0.8, 0.0}});
  LatestValueMailbox<FaceCommand> mailbox;
  ShowRecorder recorder(face, neutral);
  GamepadPuppeteer puppeteer([&](GamepadState& s) { return gp.latest(s); }, mapping, neutral,
                             mailbox, 250.0, &recorder);
  puppeteer.start();
  ASSERT_TRUE(wait_for([&] { return puppeteer.connected(); }, 3000)) << "not opened";
  // The jaw closed for 100 ms, half a second of sweep with button a pressed
  // halfway, then a hold.
  pad.report(0, -127, 0x00);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  for (int i = 0; i <= 100; ++i) {
    pad.report(0, static_cast<std::int8_t>(-127 + 2 * i), i > 50 ? 0x01 : 0x00);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  puppeteer.stop();
  FaceCommand last;
  ASSERT_TRUE(mailbox.consume(last));
  EXPECT_NEAR(last.values[face.jaw_pitch()], (9.0 + 9.0 * 73.0 / 127.0) * kDeg, 1e-9);
  EXPECT_DOUBLE_EQ(last.values[0], 0.8);

  recorder.write("/tmp/uhid_take.yaml", "uhid_take");
  const Show show = Show::load("/tmp/uhid_take.yaml", face, neutral, ExpressionLibrary{});
  std::array<double, kMaxFaceSignals> pose{};
  show.evaluate(show.duration(), pose);
  EXPECT_NEAR(pose[face.jaw_pitch()], last.values[face.jaw_pitch()], 1e-6);
  EXPECT_DOUBLE_EQ(pose[0], 0.8);
  const double end_jaw_deg = pose[face.jaw_pitch()] / kDeg;
  // It starts at the centred stick (9 degrees) and the sweep closes the jaw first.
  show.evaluate(0.0, pose);
  EXPECT_NEAR(pose[face.jaw_pitch()], 9.0 * kDeg, 1e-6);
  double lowest = 1.0;
  for (const auto& k : show.keyframes()) lowest = std::min(lowest, k.values[face.jaw_pitch()]);
  EXPECT_LT(lowest, 0.5 * kDeg);
  EXPECT_GT(show.duration(), 0.4);
  std::printf(
      "[uhid] puppeteered %llu commands; recorded %zu keyframes over %.2f s; the show "
      "loads back and ends at jaw %.2f deg\n",
      static_cast<unsigned long long>(puppeteer.published()), show.keyframes().size(),
      show.duration(), end_jaw_deg);
}

TEST(Uhid, ARealDualShock4DescriptorGivesItsLayoutThroughTheKernelAndDecodes) {
  constexpr std::uint16_t kDs4Product = 0xFACF;  // pid.codes again: hid-generic binds, not hid-sony
  VirtualGamepad pad(kDualShock4Descriptor, kDs4Product);
  std::vector<HidDeviceInfo> found;
  ASSERT_TRUE(
      wait_for([&] { return !(found = enumerate_hid(kVendor, kDs4Product)).empty(); }, 3000));
  const std::string path = found[0].path;  // /dev/hidrawN
  // The kernel holds the very bytes uhid was given (sysfs), and the layout
  // read through hidapi and HIDIOCGRDESC is the one the bytes declare.
  const std::string sysfs =
      "/sys/class/hidraw/" + path.substr(path.rfind('/') + 1) + "/device/report_descriptor";
  std::ifstream in(sysfs, std::ios::binary);
  const std::vector<std::uint8_t> kernel_bytes((std::istreambuf_iterator<char>(in)),
                                               std::istreambuf_iterator<char>());
  EXPECT_TRUE(std::equal(kernel_bytes.begin(), kernel_bytes.end(),
                         std::begin(kDualShock4Descriptor), std::end(kDualShock4Descriptor)) &&
              kernel_bytes.size() == sizeof kDualShock4Descriptor)
      << sysfs << ": " << kernel_bytes.size() << " bytes";
  const GamepadLayout read = read_gamepad_layout({path, 0, 0});
  const std::string expected = describe(gamepad_layout_from_descriptor(kDualShock4Descriptor));
  EXPECT_EQ(describe(read), expected);
  EXPECT_NE(expected.find("hat_x"), std::string::npos);

  // Read with no layout given: the descriptor decides. Left stick full left,
  // right stick down, hat south-west (5), cross and options (2, 10), L2 half.
  HidGamepad gp({path, 0, 0}, GamepadLayout{});
  GamepadState s;
  ASSERT_TRUE(wait_for([&] { return gp.latest(s) && s.connected; }, 3000)) << "not opened";
  std::uint8_t report[64] = {0x01, 0x00, 0x80, 0x80, 0xFF, 0x25, 0x20, 0x00, 0x80, 0x00};
  pad.raw_report(report);
  ASSERT_TRUE(wait_for([&] { return gp.latest(s) && s.reports > 0; }, 1000)) << "no report";
  EXPECT_EQ(gp.bad_descriptors(), 0u);
  EXPECT_DOUBLE_EQ(s.axes[0], -1.0);           // x
  EXPECT_DOUBLE_EQ(s.axes[5], 1.0);            // rz
  EXPECT_DOUBLE_EQ(s.axes[9], -1.0);           // hat_x
  EXPECT_DOUBLE_EQ(s.axes[10], 1.0);           // hat_y
  EXPECT_NEAR(s.axes[3], 1.0 / 255.0, 1e-12);  // rx, L2 at 128
  EXPECT_EQ(s.buttons, (1u << 1) | (1u << 9));
  std::printf(
      "[uhid] DualShock 4 descriptor (%zu bytes) read back through %s; its report "
      "decodes to x %+.2f rz %+.2f hat %+.0f,%+.0f buttons 0x%04X\n",
      kernel_bytes.size(), path.c_str(), s.axes[0], s.axes[5], s.axes[9], s.axes[10], s.buttons);
}

}  // namespace
}  // namespace facectl
