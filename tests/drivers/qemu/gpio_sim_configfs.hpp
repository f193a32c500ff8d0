#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>

namespace facectl::testing {

constexpr const char* kGpioSimConfigfs = "/sys/kernel/config/gpio-sim";
// run_in_qemu.sh puts the module here when build_gpio_sim.sh could build it.
constexpr const char* kGpioSimModule = "/lib/modules/gpio-sim.ko";

inline void sysfs_write(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  f.flush();
  if (!f) throw std::runtime_error("cannot write '" + text + "' to " + path);
}

inline std::string sysfs_read_line(const std::string& path) {
  std::ifstream f(path);
  std::string s;
  if (!std::getline(f, s)) throw std::runtime_error("cannot read " + path);
  return s;
}

// One gpio-sim device with one bank of 8 lines, made live through configfs
// and taken down again at the end (Documentation/admin-guide/gpio/gpio-sim.rst).
class GpioSimDevice {
 public:
  explicit GpioSimDevice(const std::string& name)
      : dir_(std::string(kGpioSimConfigfs) + "/" + name) {
    if (mkdir(dir_.c_str(), 0755) != 0) throw std::runtime_error("cannot make " + dir_);
    if (mkdir((dir_ + "/bank0").c_str(), 0755) != 0) throw std::runtime_error("no bank0");
    sysfs_write(dir_ + "/bank0/num_lines", "8");
    sysfs_write(dir_ + "/live", "1");
    chip_ = sysfs_read_line(dir_ + "/bank0/chip_name");
    lines_ = "/sys/devices/platform/" + sysfs_read_line(dir_ + "/dev_name") + "/" + chip_;
  }
  ~GpioSimDevice() {
    if (live_) sysfs_write(dir_ + "/live", "0");
    rmdir((dir_ + "/bank0").c_str());
    rmdir(dir_.c_str());
  }
  const std::string& name() const { return chip_; }
  // The switch wired to `line`: pull-up drives it high, pull-down low.
  void drive(unsigned line, bool high) {
    sysfs_write(attr(line, "pull"), high ? "pull-up" : "pull-down");
  }
  // The level the chip's pin has (an output's driven value).
  int level(unsigned line) { return std::stoi(sysfs_read_line(attr(line, "value"))); }
  void vanish() {
    sysfs_write(dir_ + "/live", "0");
    live_ = false;
  }

 private:
  std::string attr(unsigned line, const char* what) {
    return lines_ + "/sim_gpio" + std::to_string(line) + "/" + what;
  }
  std::string dir_;
  std::string chip_;
  std::string lines_;
  bool live_ = true;
};

}  // namespace facectl::testing
