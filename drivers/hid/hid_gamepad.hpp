#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "control/realtime/latest_value_mailbox.hpp"
#include "drivers/hid/gamepad_report.hpp"

namespace facectl {

struct HidDeviceInfo {
  std::string path;
  std::uint16_t vendor = 0;
  std::uint16_t product = 0;
  std::string product_name;
};

// HID devices present now (hidapi, hidraw backend). vendor/product 0 match all.
std::vector<HidDeviceInfo> enumerate_hid(std::uint16_t vendor = 0, std::uint16_t product = 0);

// Which device to use: by path, or by vendor and product (the first match).
struct HidSelector {
  std::string path;
  std::uint16_t vendor = 0;
  std::uint16_t product = 0;
};

// The layout `selector`'s device declares in its report descriptor, read
// through hidapi (hid_get_report_descriptor, hidapi 0.14's API; Debian 12
// has 0.13.1, so on Linux it reads the hidraw node's descriptor with
// HIDIOCGRDESC). Throws std::runtime_error when the device cannot be opened
// or read, std::invalid_argument when its descriptor declares no gamepad.
GamepadLayout read_gamepad_layout(const HidSelector& selector);

// A gamepad read on its own non-real-time thread through hidapi. It drains
// every queued report each pass and publishes the newest state into a
// lock-free mailbox, which the consumer (the puppeteering input thread, or a
// test) reads without waiting. Unplugged, it publishes `connected = false` and
// looks for the device again every `rescan_s`; plugged back, it resumes.
// An empty layout (no axes, no buttons) is read from the device's report
// descriptor at each open (gamepad_layout_from_descriptor).
class HidGamepad {
 public:
  HidGamepad(HidSelector selector, GamepadLayout layout, double rescan_s = 0.25);
  ~HidGamepad();
  HidGamepad(const HidGamepad&) = delete;
  HidGamepad& operator=(const HidGamepad&) = delete;

  // The newest state since the last call; false when nothing new arrived.
  bool latest(GamepadState& out) { return mailbox_.consume(out); }
  std::uint64_t opens() const { return opens_.load(); }
  std::uint64_t bad_reports() const { return bad_reports_.load(); }
  std::uint64_t bad_descriptors() const { return bad_descriptors_.load(); }

 private:
  void run();
  bool adopt_descriptor_layout(const std::string& path);

  HidSelector selector_;
  GamepadLayout layout_;
  bool layout_from_descriptor_;
  double rescan_s_;
  LatestValueMailbox<GamepadState> mailbox_;
  std::atomic<std::uint64_t> opens_{0}, bad_reports_{0}, bad_descriptors_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl
