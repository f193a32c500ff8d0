// `facectl bus doctor` for a DYNAMIXEL bus: read-only, PING and READ only.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "control/clock.hpp"
#include "drivers/bus_doctor.hpp"
#include "drivers/dynamixel/dynamixel_link.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"
#include "drivers/protocol/wire_encoding.hpp"

namespace facectl {
namespace {

using Level = DoctorFinding::Level;

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  return doctor_format(f, a, b, c);
}

// What one servo says, by PING and READ.
void examine(DoctorReport& r, DynamixelLink& link, const ActuatorModel& a,
             const DynamixelOptions& o, int samples) {
  const auto id = static_cast<std::uint8_t>(a.address);
  const std::string who = "servo " + std::to_string(a.address) + " (" + a.name + ")";
  const double wait_s = std::max(o.response_timeout_s, 0.002);
  const double delay_s = 508e-6;  // the longest Return Delay Time: the servo's may be any
  std::uint8_t tx[32];
  std::uint8_t info[3];
  std::vector<double> ms;
  const std::size_t ping = dxl2::encode_instruction(id, dxl2::kPing, {}, tx);
  for (int i = 0; i < samples; ++i) {
    const std::int64_t t0 = monotonic_ns();
    if (link.request(id, {tx, ping}, info, wait_s, delay_s) == DynamixelLink::Reply::kOk) {
      ms.push_back(static_cast<double>(monotonic_ns() - t0) * 1e-6);
    }
  }
  if (ms.empty()) {
    r.findings.push_back({Level::kProblem, who + ": no answer to " + std::to_string(samples) +
                                               " PINGs (ID, baud rate, wiring, power?)"});
    return;
  }
  const std::string round_trip = round_trip_text(ms);
  const dxl_x::Model* model = dxl_x::find_model(dxl_x::get_u16(info));
  if (model == nullptr) {
    r.findings.push_back({Level::kProblem, who + ": Model Number " +
                                               std::to_string(dxl_x::get_u16(info)) +
                                               " is not an X-series servo facectl knows"});
    return;
  }
  r.findings.push_back(
      {ms.size() == static_cast<std::size_t>(samples) ? Level::kOk : Level::kWarning,
       who + ": " + model->name + ", firmware " + std::to_string(info[2]) + ", " +
           std::to_string(ms.size()) + "/" + std::to_string(samples) + " PINGs answered, " +
           round_trip});
  const auto read = [&](std::uint16_t address, std::span<std::uint8_t> out) {
    const std::size_t n =
        dxl2::encode_read(id, address, static_cast<std::uint16_t>(out.size()), tx);
    return link.request(id, {tx, n}, out, wait_s, delay_s) == DynamixelLink::Reply::kOk;
  };
  std::uint8_t b[4];
  if (!read(dxl_x::kStatusReturnLevel, {b, 1})) {
    r.findings.push_back({Level::kWarning, who + ": does not answer READ (Status Return Level 0?)"
                                                 "; facectl sets level 2 at start"});
    return;
  }
  if (read(dxl_x::kHardwareErrorStatus, {b, 1}) && b[0] != 0) {
    r.findings.push_back(
        {Level::kProblem, who + ": Hardware Error Status: " + dxl_x::hardware_error_text(b[0]) +
                              " (torque stays off until it is power-cycled)"});
  }
  if (read(dxl_x::kTorqueEnable, {b, 1}) && b[0] != 0) {
    r.findings.push_back(
        {Level::kWarning, who + ": torque is on: another program may be driving it"});
  }
  if (read(dxl_x::kReturnDelayTime, {b, 1}) && 2 * b[0] != o.return_delay_us) {
    r.findings.push_back({Level::kOk, who + ": Return Delay Time " + std::to_string(2 * b[0]) +
                                          " us; facectl writes " +
                                          std::to_string(o.return_delay_us) +
                                          " us at start (EEPROM, once)"});
  }
  std::uint8_t feedback[dxl_x::kFeedbackLength];
  if (read(dxl_x::kFeedbackAddress, feedback)) {
    const double volts =
        0.1 * dxl_x::get_u16(feedback + (dxl_x::kPresentInputVoltage - dxl_x::kPresentLoad));
    const int celsius = feedback[dxl_x::kPresentTemperature - dxl_x::kPresentLoad];
    r.findings.push_back({Level::kOk, who + fmt(": %.1f V, %.0f deg C", volts, celsius)});
    const WireEncoding enc(a.kind, a.encoding);
    const double at =
        enc.decode(dxl_x::get_i32(feedback + (dxl_x::kPresentPosition - dxl_x::kPresentLoad)));
    check_hard_range(r, who, a, at, "its encoding");
  }
}

}  // namespace

DoctorReport diagnose_dynamixel(const std::string& bus, const std::string& device, long baud,
                                const std::vector<ActuatorModel>& actuators,
                                const DynamixelOptions& options, int samples) {
  DoctorReport r;
  r.bus = bus + " (DYNAMIXEL " + device + " " + std::to_string(baud) + " baud)";
  const auto link = doctor_open<DynamixelLink>(r, device, baud);
  if (link == nullptr) return r;
  for (const ActuatorModel& a : actuators) examine(r, *link, a, options, samples);
  // Who is on the bus: every servo answers a broadcast PING, one after the
  // other, each after its own return delay (up to 508 us).
  std::uint8_t tx[16];
  const std::size_t n = dxl2::encode_instruction(dxl2::kBroadcastId, dxl2::kPing, {}, tx);
  std::set<int> heard;
  if (link->send({tx, n}, 50'000'000)) {
    const double window_s = 253 * (link->wire_s(14) + 508e-6) + 0.02;
    link->receive(
        253, monotonic_ns() + static_cast<std::int64_t>(window_s * 1e9),
        [&](std::uint8_t id, std::uint8_t, std::span<const std::uint8_t>) { heard.insert(id); });
  }
  std::set<int> rig;
  for (const ActuatorModel& a : actuators) rig.insert(a.address);
  for (const int id : heard) {
    if (rig.count(id) == 0) {
      r.findings.push_back({Level::kWarning, "servo ID " + std::to_string(id) +
                                                 " answers but is not in the rig (two servos "
                                                 "with one ID garble each other's replies)"});
    }
  }
  r.findings.push_back(
      {Level::kOk, std::to_string(heard.size()) + " servo(s) answered a broadcast PING"});
  return r;
}

}  // namespace facectl
