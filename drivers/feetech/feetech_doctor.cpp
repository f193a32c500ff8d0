// `facectl bus doctor` for a Feetech bus: read-only, PING and READ only.
#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>

#include "control/clock.hpp"
#include "drivers/bus_doctor.hpp"
#include "drivers/feetech/feetech_link.hpp"
#include "drivers/protocol/feetech_packet.hpp"
#include "drivers/protocol/feetech_table.hpp"
#include "drivers/protocol/wire_encoding.hpp"

namespace facectl {
namespace {

using Level = DoctorFinding::Level;

constexpr double kLongestReturnDelayS = 508e-6;  // Return Delay 254 x 2 us: a servo's may be any

// Every flag set in a status packet's error byte, by name.
std::string error_bits_text(std::uint8_t bits) {
  std::string text;
  for (int k = 0; k < 8; ++k) {
    const auto bit = static_cast<std::uint8_t>(1u << k);
    if ((bits & bit) == 0) continue;
    const std::string name = ft::error_text(bit);
    text +=
        (text.empty() ? "" : ", ") + (name == "unknown bit" ? "bit " + std::to_string(k) : name);
  }
  return text;
}

// What one servo says, by PING and READ.
void examine(DoctorReport& r, FeetechLink& link, const ActuatorModel& a, const FeetechOptions& o,
             int samples) {
  const auto id = static_cast<std::uint8_t>(a.address);
  const std::string who = "servo " + std::to_string(a.address) + " (" + a.name + ")";
  const double wait_s = std::max(o.response_timeout_s, 0.002);
  std::uint8_t tx[16];
  std::uint8_t error = 0, errors = 0;
  std::vector<double> ms;
  const std::size_t ping = scs::encode_instruction(id, scs::kPing, {}, tx);
  for (int i = 0; i < samples; ++i) {
    const std::int64_t t0 = monotonic_ns();
    if (link.request(id, {tx, ping}, {}, wait_s, kLongestReturnDelayS, &error) ==
        FeetechLink::Reply::kOk) {
      ms.push_back(static_cast<double>(monotonic_ns() - t0) * 1e-6);
      errors |= error;
    }
  }
  if (ms.empty()) {
    r.findings.push_back({Level::kProblem, who + ": no answer to " + std::to_string(samples) +
                                               " PINGs (ID, baud rate, series, wiring, power?)"});
    return;
  }
  const std::string round_trip = round_trip_text(ms);
  const auto read = [&](std::uint8_t address, std::span<std::uint8_t> out) {
    const std::size_t n = scs::encode_read(id, address, static_cast<std::uint8_t>(out.size()), tx);
    const bool ok = link.request(id, {tx, n}, out, wait_s, kLongestReturnDelayS, &error) ==
                    FeetechLink::Reply::kOk;
    if (ok) errors |= error;
    return ok;
  };
  std::uint8_t b[ft::kFeedbackLength];
  // The model number only: the table facectl uses has no firmware version.
  const std::string model = read(ft::kModel, {b, 2})
                                ? "model number " + std::to_string(ft::get_u16(o.series, b))
                                : "model number unreadable";
  r.findings.push_back(
      {ms.size() == static_cast<std::size_t>(samples) ? Level::kOk : Level::kWarning,
       who + ": " + model + ", " + std::to_string(ms.size()) + "/" + std::to_string(samples) +
           " PINGs answered, " + round_trip});
  if (read(ft::kTorqueEnable, {b, 1}) && b[0] != 0) {
    r.findings.push_back(
        {Level::kWarning, who + ": torque is on: another program may be driving it"});
  }
  if (read(ft::kResponseLevel, {b, 1}) && b[0] == 0) {
    r.findings.push_back({Level::kOk, who + ": Response Level 0 (answers PING and READ only); "
                                            "facectl sets 1 at start"});
  }
  if (read(ft::kReturnDelay, {b, 1}) && 2 * b[0] != o.return_delay_us) {
    r.findings.push_back(
        {Level::kOk, who + ": Return Delay " + std::to_string(2 * b[0]) + " us; facectl writes " +
                         std::to_string(o.return_delay_us) + " us at start (EEPROM, once)"});
  }
  if (read(ft::kFeedbackAddress, {b, ft::kFeedbackLength})) {
    const double volts = 0.1 * b[ft::kPresentVoltage - ft::kFeedbackAddress];
    const int celsius = b[ft::kPresentTemperature - ft::kFeedbackAddress];
    r.findings.push_back({Level::kOk, who + doctor_format(": %.1f V, %.0f deg C", volts, celsius)});
    const WireEncoding enc(a.kind, a.encoding);
    const double at = enc.decode(ft::get_u16(o.series, b));
    check_hard_range(r, who, a, at, "its encoding and series");
  }
  if (errors != 0) {
    r.findings.push_back({Level::kProblem, who + ": error status: " + error_bits_text(errors) +
                                               " (facectl keeps its torque off until it clears)"});
  }
}

}  // namespace

DoctorReport diagnose_feetech(const std::string& bus, const std::string& device, long baud,
                              const std::vector<ActuatorModel>& actuators,
                              const FeetechOptions& options, int samples) {
  DoctorReport r;
  r.bus = bus + " (Feetech " + (options.series == ft::Series::kSts ? "STS " : "SCS ") + device +
          " " + std::to_string(baud) + " baud)";
  const auto link = doctor_open<FeetechLink>(r, device, baud);
  if (link == nullptr) return r;
  std::set<int> rig;
  for (const ActuatorModel& a : actuators) {
    examine(r, *link, a, options, samples);
    rig.insert(a.address);
  }
  // Who else answers: one PING to each ID up to kFeetechScanLastId. The
  // protocol has no broadcast PING whose replies take turns (DYNAMIXEL 2.0's
  // do), so each ID is asked on its own; the bound keeps this well under a
  // second.
  const double wait_s = std::max(options.response_timeout_s, 0.002);
  std::uint8_t tx[16];
  int heard = 0;
  for (int id = 0; id <= kFeetechScanLastId; ++id) {
    if (rig.count(id) != 0) continue;
    const std::size_t n =
        scs::encode_instruction(static_cast<std::uint8_t>(id), scs::kPing, {}, tx);
    if (link->request(static_cast<std::uint8_t>(id), {tx, n}, {}, wait_s, kLongestReturnDelayS) !=
        FeetechLink::Reply::kOk) {
      continue;
    }
    ++heard;
    r.findings.push_back({Level::kWarning, "servo ID " + std::to_string(id) +
                                               " answers but is not in the rig (two servos "
                                               "with one ID garble each other's replies)"});
  }
  r.findings.push_back({Level::kOk, "IDs 0.." + std::to_string(kFeetechScanLastId) +
                                        " not in the rig: " + std::to_string(heard) +
                                        " answered a PING"});
  return r;
}

}  // namespace facectl
