#include "drivers/hid/hid_gamepad.hpp"

#include <fcntl.h>
#include <hidapi/hidapi.h>
#include <linux/hidraw.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "control/clock.hpp"
#include "drivers/hid/gamepad_descriptor_layout.hpp"

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

// The device's report descriptor as the kernel holds it (linux/hidraw.h).
// hidapi 0.13 (Debian 12) has no hid_get_report_descriptor; its hidraw
// backend's paths are the /dev/hidrawN nodes this reads.
std::vector<std::uint8_t> read_hidraw_descriptor(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(path + ": " + std::strerror(errno));
  int size = 0;
  hidraw_report_descriptor rd{};
  const bool ok = ioctl(fd, HIDIOCGRDESCSIZE, &size) == 0 && size >= 0 &&
                  size <= HID_MAX_DESCRIPTOR_SIZE &&
                  (rd.size = static_cast<__u32>(size), ioctl(fd, HIDIOCGRDESC, &rd) == 0);
  const int err = errno;
  ::close(fd);
  if (!ok) throw std::runtime_error(path + ": HIDIOCGRDESC: " + std::strerror(err));
  return {rd.value, rd.value + rd.size};
}

// The hidraw path of an open device.
std::string device_path(hid_device* dev) {
  const hid_device_info* info = hid_get_device_info(dev);
  return info != nullptr && info->path != nullptr ? info->path : "";
}

hid_device* open_device(const HidSelector& s) {
  return !s.path.empty() ? hid_open_path(s.path.c_str()) : hid_open(s.vendor, s.product, nullptr);
}

}  // namespace

GamepadLayout read_gamepad_layout(const HidSelector& selector) {
  init_hidapi();
  hid_device* dev = open_device(selector);
  if (dev == nullptr) {
    char id[16];
    std::snprintf(id, sizeof id, "%04x:%04x", selector.vendor, selector.product);
    throw std::runtime_error("cannot open HID device " +
                             (selector.path.empty() ? id : selector.path) +
                             " (absent, or no permission on its hidraw node)");
  }
  const std::string path = device_path(dev);
  hid_close(dev);
  const std::vector<std::uint8_t> rd = read_hidraw_descriptor(path);
  return gamepad_layout_from_descriptor(rd);
}

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
    : selector_(std::move(selector)),
      layout_(std::move(layout)),
      layout_from_descriptor_(layout_.axes.empty() && layout_.buttons.empty()),
      rescan_s_(rescan_s) {
  validate(layout_);
  init_hidapi();
  thread_ = std::thread([this] { run(); });
}

HidGamepad::~HidGamepad() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

// Each open, since a different pad may have been plugged in. On failure the
// device is treated as absent (the face eases to neutral) and retried.
bool HidGamepad::adopt_descriptor_layout(const std::string& path) {
  try {
    layout_ = gamepad_layout_from_descriptor(read_hidraw_descriptor(path));
    return true;
  } catch (const std::exception& e) {
    if (bad_descriptors_.fetch_add(1) == 0) {
      std::fprintf(stderr, "facectl: gamepad %s: %s\n", path.c_str(), e.what());
    }
    return false;
  }
}

void HidGamepad::run() {
  hid_device* dev = nullptr;
  GamepadState state;
  std::uint8_t buf[64];
  while (!stop_.load()) {
    if (dev == nullptr) {
      dev = open_device(selector_);
      if (dev != nullptr && layout_from_descriptor_ && !adopt_descriptor_layout(device_path(dev))) {
        hid_close(dev);
        dev = nullptr;
      }
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
