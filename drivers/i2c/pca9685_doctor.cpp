#include "drivers/i2c/pca9685_doctor.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include "control/clock.hpp"
#include "drivers/protocol/pca9685_registers.hpp"

namespace facectl {

using Level = DoctorFinding::Level;

DoctorReport diagnose_pca9685(const std::string& bus, I2cTransport& transport,
                              const std::vector<ActuatorModel>& actuators,
                              const Pca9685Options& options, int samples) {
  using namespace pca9685;
  DoctorReport r;
  char buf[320];
  const int want = prescale_for(options.pwm_hz);
  std::snprintf(buf, sizeof buf, "%s (PCA9685 on %s, PWM %.2f Hz: PRE_SCALE %d)", bus.c_str(),
                transport.where().c_str(), frequency_of(want), want);
  r.bus = buf;
  const int boards = static_cast<int>(options.boards.size());
  std::set<int> used;
  for (const ActuatorModel& a : actuators) {
    if (a.address >= 1 && a.address <= kChannels * boards) used.insert((a.address - 1) / kChannels);
  }
  for (int i = 0; i < boards; ++i) {
    const int address = options.boards[static_cast<std::size_t>(i)];
    int mode1 = -1, mode2 = -1, prescale = -1, failures = 0;
    std::int64_t worst_ns = 0;
    for (int s = 0; s < samples; ++s) {
      const std::int64_t t0 = monotonic_ns();
      const int m1 = transport.read_byte(address, kMode1);
      const int m2 = transport.read_byte(address, kMode2);
      const int ps = transport.read_byte(address, kPreScale);
      worst_ns = std::max(worst_ns, monotonic_ns() - t0);
      if (m1 < 0 || m2 < 0 || ps < 0) {
        ++failures;
        continue;
      }
      mode1 = m1, mode2 = m2, prescale = ps;
    }
    if (mode1 < 0) {
      std::snprintf(buf, sizeof buf, "board 0x%02x: not answering (%d of %d reads failed)", address,
                    failures, samples);
      r.findings.push_back({Level::kProblem, buf});
      continue;
    }
    std::snprintf(buf, sizeof buf,
                  "board 0x%02x: MODE1 0x%02x%s, MODE2 0x%02x, PRE_SCALE %d = %.2f Hz; "
                  "3 reads in at most %.2f ms%s",
                  address, mode1, (mode1 & kMode1Sleep) ? " (asleep)" : "", mode2, prescale,
                  frequency_of(prescale), static_cast<double>(worst_ns) * 1e-6,
                  failures > 0 ? "; some reads failed" : "");
    r.findings.push_back({failures > 0 ? Level::kWarning : Level::kOk, buf});
    if ((mode1 & kMode1ExtClk) != 0) {
      std::snprintf(buf, sizeof buf,
                    "board 0x%02x: EXTCLK is set (only a power cycle clears it): its frequency "
                    "is not the internal 25 MHz one, and start-up will refuse it",
                    address);
      r.findings.push_back({Level::kProblem, buf});
    }
    if (prescale != want && (mode1 & kMode1Sleep) == 0) {
      std::snprintf(buf, sizeof buf,
                    "board 0x%02x: running at PRE_SCALE %d, not %d: facectl sets it at start-up",
                    address, prescale, want);
      r.findings.push_back({Level::kWarning, buf});
    }
    if (used.count(i) == 0) {
      std::snprintf(buf, sizeof buf, "board 0x%02x: no actuator on it (addresses %d..%d)", address,
                    i * kChannels + 1, (i + 1) * kChannels);
      r.findings.push_back({Level::kWarning, buf});
    }
  }
  return r;
}

}  // namespace facectl
