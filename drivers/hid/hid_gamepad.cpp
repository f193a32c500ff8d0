#include "drivers/hid/hid_gamepad.hpp"

#include <hidapi/hidapi.h>

#include <chrono>
#include <mutex>

#include "control/clock.hpp"

namespace facectl {

namespace {
std::string narrow(const wchar_t* w) {
  std::string s;
  for (; w != nullptr && *w != 0; ++w) s += *w < 128 ? static_cast<char>(*w) : '?';
  return s;
}
// hid_init is not thread-safe; every user goes through here once.
void init_hidapi() {
  static std::once_flag once;
  std::call_once(once, [] { hid_init(); });
}
}  // namespace

std::vector<HidDeviceInfo> enumerate_hid(std::uint16_t vendor, std::uint16_t product) {
  init_hidapi();
  std::vector<HidDeviceInfo> out;
  hid_device_info* list = hid_enumerate(vendor, product);
  for (hid_device_info* d = list; d != nullptr; d = d->next) {
    out.push_back({d->path != nullptr ? d->path : "", d->vendor_id, d->product_id,
                   narrow(d->product_string)});
  }
  hid_free_enumeration(list);
  return out;
}

HidGamepad::HidGamepad(HidSelector selector, GamepadLayout layout, double rescan_s)
    : selector_(std::move(selector)), layout_(std::move(layout)), rescan_s_(rescan_s) {
  validate(layout_);
  init_hidapi();
  thread_ = std::thread([this] { run(); });
}

HidGamepad::~HidGamepad() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void HidGamepad::run() {
  hid_device* dev = nullptr;
  GamepadState state;
  std::uint8_t buf[64];
  while (!stop_.load()) {
    if (dev == nullptr) {
      dev = !selector_.path.empty() ? hid_open_path(selector_.path.c_str())
                                    : hid_open(selector_.vendor, selector_.product, nullptr);
      if (dev == nullptr) {
        std::this_thread::sleep_for(std::chrono::duration<double>(rescan_s_));
        continue;
      }
      opens_.fetch_add(1);
      state.connected = true;
      mailbox_.publish(state);
    }
    // Wait up to 20 ms for a report, then drain whatever else is queued, so a
    // backlog of stale reports never builds up.
    int n = hid_read_timeout(dev, buf, sizeof buf, 20);
    bool fresh = false;
    while (n > 0) {
      if (decode_gamepad_report(
              layout_, std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)), state)) {
        ++state.reports;
        state.received_ns = monotonic_ns();
        fresh = true;
      } else {
        bad_reports_.fetch_add(1);
      }
      n = hid_read_timeout(dev, buf, sizeof buf, 0);
    }
    if (fresh) mailbox_.publish(state);
    if (n < 0) {  // unplugged
      hid_close(dev);
      dev = nullptr;
      state.connected = false;
      mailbox_.publish(state);
    }
  }
  if (dev != nullptr) hid_close(dev);
}

}  // namespace facectl
