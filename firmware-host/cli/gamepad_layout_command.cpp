#include "firmware-host/cli/gamepad_layout_command.hpp"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "drivers/hid/gamepad_descriptor_layout.hpp"
#include "drivers/hid/hid_gamepad.hpp"

namespace facectl {
namespace {

HidSelector parse_device(const std::string& device) {
  HidSelector s;
  const auto colon = device.find(':');
  if (device.rfind("/", 0) == 0 || colon == std::string::npos) {
    s.path = device;
    return s;
  }
  std::size_t end1 = 0, end2 = 0;
  const std::string v = device.substr(0, colon), p = device.substr(colon + 1);
  try {
    s.vendor = static_cast<std::uint16_t>(std::stoul(v, &end1, 16));
    s.product = static_cast<std::uint16_t>(std::stoul(p, &end2, 16));
  } catch (const std::exception&) {
    end1 = 0;
  }
  if (end1 != v.size() || end2 != p.size() || s.vendor == 0 || s.product == 0) {
    throw std::invalid_argument(
        "--device: expected a hidraw path or VENDOR:PRODUCT in hex, found '" + device + "'");
  }
  return s;
}

// Binary as the kernel gives it (/sys/class/hidraw/*/device/report_descriptor),
// or hex bytes separated by white space (tests/drivers/hid_descriptors/).
std::vector<std::uint8_t> read_descriptor_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool hex = bytes.find_first_not_of("0123456789abcdefABCDEF \t\r\n") == std::string::npos;
  if (!hex) return {bytes.begin(), bytes.end()};
  std::vector<std::uint8_t> out;
  std::size_t i = 0;
  while ((i = bytes.find_first_not_of(" \t\r\n", i)) != std::string::npos) {
    const std::size_t j = std::min(bytes.find_first_of(" \t\r\n", i), bytes.size());
    if (j - i != 2) throw std::invalid_argument(path + ": expected hex bytes of two digits");
    out.push_back(static_cast<std::uint8_t>(std::stoul(bytes.substr(i, 2), nullptr, 16)));
    i = j;
  }
  return out;
}

}  // namespace

int gamepad_layout_command(const GamepadLayoutOptions& options) {
  try {
    if (options.device.empty() == options.descriptor.empty()) {
      throw std::invalid_argument("expected exactly one of --device and --descriptor");
    }
    const GamepadLayout layout =
        options.descriptor.empty()
            ? read_gamepad_layout(parse_device(options.device))
            : gamepad_layout_from_descriptor(read_descriptor_file(options.descriptor));
    std::printf("%s", describe(layout).c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl gamepad layout: %s\n", e.what());
    return 2;
  }
}

}  // namespace facectl
